#!/usr/bin/python3
"""Write a CalculiX input for Hertz H from the two gmsh meshes of contact2d.

    ccx_inp.py BLOCK.msh DISK.msh OUT.inp [KFACTOR]

Plane strain CPE3 (P1 triangles) or CPE6 (P2 triangles, from second-order
gmsh meshes: the node order of gmsh's type 9 is CalculiX's) of thickness 1,
E = 200000, nu = 0.3.  Block
bottom clamped, disk top ux = 0, uy = -0.01.  Frictionless surface-to-surface
penalty contact, slave = block top, master = disk arc, linear pressure-
overclosure with slope K = KFACTOR * E (default 500).  Output: total reaction
on the disk top (*NODE PRINT, TOTALS=ONLY), contact stresses (*CONTACT FILE)
and displacements (*NODE FILE).
Block nodes/elements keep their gmsh ids; the disk's follow them (ccx sizes
its arrays by the largest id, so the ids are kept compact).
"""
import sys

from msh22 import physical_names, read_msh

E, NU, DELTA = 200000.0, 0.3, 0.01


def faces(tris, edges, eoff):
    """Element faces (element id, S1..S3) of the boundary edges."""
    where = {}
    for k, t in enumerate(tris):
        for f, (i, j) in enumerate(((0, 1), (1, 2), (2, 0))):
            where[frozenset((t[i], t[j]))] = (k + 1 + eoff, f + 1)
    return [where[frozenset(e[:2])] for e in edges]


def write_inp(bfile, dfile, out, kfac=500.0):
    """Write the CalculiX input OUT for the meshes BFILE (block), DFILE (disk)."""
    bn, bt, bl = read_msh(bfile)
    dn, dt, dl = read_msh(dfile)
    bp, dp = physical_names(bfile), physical_names(dfile)
    noff, eoff = max(bn), len(bt)
    o = []
    o.append("*HEADING\nHertz H: half-disk pressed onto a block, plane strain")
    o.append("*NODE, NSET=NALL")
    o += [f"{i},{x:.13g},{y:.13g}" for i, (x, y) in bn.items()]   # ccx reads at most 20 characters
    o += [f"{i + noff},{x:.13g},{y:.13g}" for i, (x, y) in dn.items()]
    etype = "CPE6" if len(bt[0]) == 6 else "CPE3"
    o.append(f"*ELEMENT, TYPE={etype}, ELSET=EBLOCK")
    o += [f"{k + 1}," + ",".join(str(n) for n in t) for k, t in enumerate(bt)]
    o.append(f"*ELEMENT, TYPE={etype}, ELSET=EDISK")
    o += [f"{k + 1 + eoff}," + ",".join(str(n + noff) for n in t) for k, t in enumerate(dt)]

    def nset(name, ids):
        ids = sorted(set(ids))
        o.append(f"*NSET, NSET={name}")
        o.extend(",".join(str(i) for i in ids[k:k + 16]) for k in range(0, len(ids), 16))

    nset("NBOT", [n for e in bl[bp["bottom"][1]] for n in e])
    nset("NTOP", [n + noff for e in dl[dp["top"][1]] for n in e])
    o.append("*SURFACE, NAME=SSLAVE, TYPE=ELEMENT")
    o += [f"{e},S{f}" for e, f in faces(bt, bl[bp["top"][1]], 0)]
    o.append("*SURFACE, NAME=SMASTER, TYPE=ELEMENT")
    arc = [tuple(n + noff for n in e) for e in dl[dp["arc"][1]]]
    dto = [tuple(n + noff for n in t) for t in dt]
    o += [f"{e},S{f}" for e, f in faces(dto, arc, eoff)]
    o.append("*MATERIAL, NAME=STEEL\n*ELASTIC\n%r,%r" % (E, NU))
    o.append("*SOLID SECTION, ELSET=EBLOCK, MATERIAL=STEEL\n1.")
    o.append("*SOLID SECTION, ELSET=EDISK, MATERIAL=STEEL\n1.")
    o.append("*SURFACE INTERACTION, NAME=SI")
    o.append("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n%r" % (kfac * E))
    o.append("*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSSLAVE,SMASTER")
    o.append("*BOUNDARY\nNBOT,1,2,0.\nNTOP,1,1,0.\nNTOP,2,2,%r" % (-DELTA))
    o.append("*STEP\n*STATIC\n1.,1.")
    o.append("*NODE PRINT, NSET=NTOP, TOTALS=ONLY\nRF")
    o.append("*NODE FILE\nU")
    o.append("*CONTACT FILE\nCSTR")
    o.append("*END STEP")
    with open(out, "w") as f:
        f.write("\n".join(o) + "\n")


if __name__ == "__main__":
    write_inp(sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) > 4 else 500.0)
