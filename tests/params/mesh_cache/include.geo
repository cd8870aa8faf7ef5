// block.geo read through Include: a mesh the cache cannot key (the included file is not in the key)
Include "block.geo";
