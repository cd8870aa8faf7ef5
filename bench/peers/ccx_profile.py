#!/usr/bin/python3
"""CalculiX Hertz output -> profile file (see hertz_err.py).

    ccx_profile.py BLOCK.msh DISK.msh JOB OUT.prof
P is |fy| of the last "total force" block of JOB.dat (the reaction on the
disk top); the pressure is CPRESS of the last CONTACT block of JOB.frd at the
block top nodes (their ids are the gmsh ids, see ccx_inp.py; a top node
absent from the block has pressure 0).
"""
import sys

from hertz_err import write_profile
from msh22 import physical_names, read_msh


def ccx_profile(bfile, dfile, job, out):
    """Write the profile of one CalculiX run."""
    bn, _, bl = read_msh(bfile)
    dn = read_msh(dfile)[0]
    top = sorted({n for e in bl[physical_names(bfile)["top"][1]] for n in e})
    P = None
    with open(job + ".dat") as f:
        lines = f.readlines()
    for k, ln in enumerate(lines):
        if "total force" in ln:
            for nxt in lines[k + 1:k + 4]:
                w = nxt.split()
                if len(w) == 3:
                    P = abs(float(w[1]))
                    break
    if P is None:
        raise ValueError(f"{job}.dat: no total force")
    cpress, block = {}, None
    with open(job + ".frd") as f:
        for ln in f:
            if ln.startswith(" -4"):
                block = ln.split()[1]
                if block == "CONTACT":
                    cpress = {}
            elif ln.startswith(" -3"):
                block = None
            elif block == "CONTACT" and ln.startswith(" -1"):
                # fixed format: " -1", node I10, values E12.5 (they may touch)
                s = ln.rstrip("\n")
                vals = [float(s[13 + 12 * i:25 + 12 * i]) for i in range((len(s) - 13) // 12)]
                cpress[int(s[3:13])] = vals[3]          # COPEN CSLIP1 CSLIP2 CPRESS ...
    if not cpress:
        raise ValueError(f"{job}.frd: no CONTACT block")
    write_profile(out, [bn[n][0] for n in top], [cpress.get(n, 0.0) for n in top],
                  P=P, dofs=2 * (len(bn) + len(dn)))


if __name__ == "__main__":
    ccx_profile(*sys.argv[1:5])
