#!/usr/bin/python3
"""CalculiX Hertz output -> profile file (see hertz_err.py and ref_err.py) and
displacement field (VTK, see field_vtk.py).

    ccx_profile.py BLOCK.msh DISK.msh JOB OUT.prof [OUT.vtk]
P is |fy| of the last "total force" block of JOB.dat (the reaction on the
disk top); the pressure is CPRESS of the last CONTACT block of JOB.frd at the
block top nodes (their ids are the gmsh ids, see ccx_inp.py; a top node
absent from the block has pressure 0); the profile's order is the meshes'
(2 for CPE6).  The displacement is the last DISP block of JOB.frd (the disk's
ids shifted as in ccx_inp.py).
"""
import sys

from field_vtk import write_vtk
from hertz_err import write_profile
from msh22 import physical_names, read_msh


def frd_blocks(path, names):
    """{name: {node id: values}} of the last result block of each name in a .frd file."""
    out, cur, block = {}, None, None
    with open(path) as f:
        for ln in f:
            if ln.startswith(" -4"):
                block = ln.split()[1]
                if block in names:
                    cur = out[block] = {}
            elif ln.startswith(" -3"):
                block = None
            elif block in names and ln.startswith(" -1"):
                # fixed format: " -1", node I10, values E12.5 (they may touch)
                s = ln.rstrip("\n")
                cur[int(s[3:13])] = [float(s[13 + 12 * i:25 + 12 * i]) for i in range((len(s) - 13) // 12)]
    return out


def ccx_profile(bfile, dfile, job, out, vtk=None):
    """Write the profile (and the displacement VTK) of one CalculiX run."""
    bn, bt, bl = read_msh(bfile)
    dn, dt, _ = read_msh(dfile)
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
    res = frd_blocks(job + ".frd", ("CONTACT", "DISP"))
    if not res.get("CONTACT"):
        raise ValueError(f"{job}.frd: no CONTACT block")
    cpress = {n: v[3] for n, v in res["CONTACT"].items()}          # COPEN CSLIP1 CSLIP2 CPRESS ...
    order = 2 if len(bt[0]) == 6 else 1
    write_profile(out, [bn[n][0] for n in top], [cpress.get(n, 0.0) for n in top],
                  P=P, dofs=2 * (len(bn) + len(dn)), order=order)
    if vtk is not None:
        u = res.get("DISP")
        if not u:
            raise ValueError(f"{job}.frd: no DISP block")
        noff = max(bn)
        write_vtk(vtk, [(bn, bt, {n: u[n][:2] for n in bn}),
                        (dn, dt, {n: u[n + noff][:2] for n in dn})], order)


if __name__ == "__main__":
    ccx_profile(*sys.argv[1:6])
