"""Legacy ASCII VTK file of a displacement field on P1 or P2 triangles, in
the layout contact2d writes (POINTS, CELLS, CELL_TYPES, POINT_DATA VECTORS
displacement, CELL_DATA SCALARS body), so that the energy error tools
(h1_err.py; studies/c2dh1.f90 for P1) measure a peer's field the same way as
contact2d's.

write_vtk(path, parts, order=1)
    parts: list of (nodes, tris, disp), one per body in the deck's body order:
    nodes dict id -> (x, y), tris list of node-id tuples, disp dict id ->
    (ux, uy) at every node used.  order 1: the first three entries of each
    tuple (the corners), VTK triangles (type 5); order 2: six entries, the
    corners and the midside nodes 12, 23, 31 (gmsh's order), VTK quadratic
    triangles (type 22).
"""


def write_vtk(path, parts, order=1):
    """Write the bodies of parts into one VTK file (body numbers 1, 2, ...)."""
    nn = 3 if order == 1 else 6
    pts, cells, body, disp = [], [], [], []
    for b, (nodes, tris, u) in enumerate(parts, start=1):
        index = {}
        for t in tris:
            for n in t[:nn]:
                if n not in index:
                    index[n] = len(pts)
                    pts.append(nodes[n])
                    disp.append(u[n])
            cells.append([index[n] for n in t[:nn]])
            body.append(b)
    o = ["# vtk DataFile Version 3.0", "peer field", "ASCII", "DATASET UNSTRUCTURED_GRID",
         f"POINTS {len(pts)} double"]
    o += [f"{x!r} {y!r} 0" for x, y in pts]
    o.append(f"CELLS {len(cells)} {(nn + 1) * len(cells)}")
    o += [f"{nn} " + " ".join(str(k) for k in c) for c in cells]
    o.append(f"CELL_TYPES {len(cells)}")
    o += ["5" if nn == 3 else "22"] * len(cells)
    o += [f"POINT_DATA {len(pts)}", "VECTORS displacement double"]
    o += [f"{ux!r} {uy!r} 0" for ux, uy in disp]
    o += [f"CELL_DATA {len(cells)}", "SCALARS body int 1", "LOOKUP_TABLE default"]
    o += [str(b) for b in body]
    with open(path, "w") as f:
        f.write("\n".join(o) + "\n")
