"""Minimal reader of gmsh MSH 2.2 ASCII 2D meshes (triangles and boundary lines,
first or second order).

read_msh(path) -> (nodes, tris, lines)
    nodes: dict node id -> (x, y)
    tris:  list of (n1, n2, n3) node ids (first-order triangles, type 2), or of
           (n1, n2, n3, n12, n23, n31) (second-order, type 9: corners, then
           the midside nodes in gmsh's order)
    lines: dict physical tag -> list of (n1, n2) (first-order lines, type 1)
           or (n1, n2, n12) (second-order, type 8)
physical_names(path) -> dict name -> (dim, tag)
"""


def _sections(path):
    with open(path) as f:
        lines = f.read().split("\n")
    sec, name = {}, None
    for ln in lines:
        s = ln.strip()
        if s.startswith("$End"):
            name = None
        elif s.startswith("$"):
            name = s[1:]
            sec[name] = []
        elif name is not None and s:
            sec[name].append(s)
    return sec


def physical_names(path):
    sec = _sections(path)
    out = {}
    for s in sec.get("PhysicalNames", [])[1:]:
        dim, tag, name = s.split(None, 2)
        out[name.strip('"')] = (int(dim), int(tag))
    return out


def read_msh(path):
    sec = _sections(path)
    if sec["MeshFormat"][0].split()[0] not in ("2.2", "2"):
        raise ValueError(f"{path}: MSH 2.2 expected")
    nodes = {}
    for s in sec["Nodes"][1:]:
        w = s.split()
        nodes[int(w[0])] = (float(w[1]), float(w[2]))
    tris, lines = [], {}
    for s in sec["Elements"][1:]:
        w = [int(v) for v in s.split()]
        etype, ntag = w[1], w[2]
        phys = w[3] if ntag > 0 else 0
        conn = w[3 + ntag:]
        if etype in (2, 9):
            tris.append(tuple(conn))
        elif etype in (1, 8):
            lines.setdefault(phys, []).append(tuple(conn))
    return nodes, tris, lines
