"""mirror_msh.py IN.msh OUT.msh: the mirror image of a MSH 2.2 ASCII mesh about
y = 0 (y -> -y on every node, the node order of triangles and quadrangles
reversed so that they keep a positive orientation; of 6-, 8- and 9-node
elements the corners reversed from the first and the mid-side nodes with
them).  The two meshes of a mirror-symmetric scene are then exact mirror
images, node for node."""
import sys

lines = open(sys.argv[1]).read().split("\n")
out, i = [], 0
while i < len(lines):
    line = lines[i]
    out.append(line)
    i += 1
    if line not in ("$Nodes", "$Elements"):
        continue
    n = int(lines[i])
    out.append(lines[i])
    i += 1
    for _ in range(n):
        f = lines[i].split()
        i += 1
        if line == "$Nodes":
            f[2] = repr(-float(f[2]))
        elif f[1] in ("2", "3"):
            nt = int(f[2])
            f = f[:3 + nt] + f[3 + nt:][::-1]
        elif f[1] in ("9", "16", "10"):         # tri6, quad8, quad9: gmsh's node order
            nt = int(f[2])
            v = f[3 + nt:]
            k = 3 if f[1] == "9" else 4
            c, m = v[:k], v[k:2 * k]
            f = f[:3 + nt] + [c[0]] + c[1:][::-1] + m[::-1] + v[2 * k:]
        out.append(" ".join(f))
open(sys.argv[2], "w").write("\n".join(out))
