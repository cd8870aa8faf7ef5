#!/usr/bin/python3
"""GetFEM 5.4 solution of Hertz H on the two gmsh meshes of contact2d.

    getfem_hertz.py BLOCK.msh DISK.msh OUT.prof [MAX_RES [MAX_ITER [DEGREE [OUT.vtk]]]]

Plane strain elasticity on each body (E = 200000, nu = 0.3), FEM_PK(2, DEGREE)
(DEGREE 1, the default, or 2) on the first-order (straight-edged) gmsh
meshes: with the curved second-order meshes the nodal contact brick stops in
its projection onto the master ("Iterative pojection on convex face did not
converge", GetFEM 5.4.2, Hertz hc = 0.02), so P2 runs on the polygonal disk.
Dirichlet conditions by multipliers (block bottom clamped; disk top ux = 0,
uy = -0.01), frictionless contact by the nodal contact brick between non-
matching meshes (slave: block top nodes, master: disk arc; non-symmetric
Alart-Curnier augmented Lagrangian, r = E), Newton with MUMPS.  The mesh
regions are the gmsh physical tags (block: bottom 1, top 3; disk: arc 1,
top 2).  Writes the profile (x, nodal normal force / lumped weight) of the
block top nodes with P = the vertical reaction on the disk top (the integral
of the Dirichlet multiplier) and the Newton outcome.  The lumped weight is the
row sum of the trace mass matrix: half of each neighbouring edge for P1, and
Simpson's weights for P2 (a corner takes h/6 of each edge, a midside node
2h/3), so that a uniform pressure is read back exactly.  With OUT.vtk the
displacement goes there too (field_vtk.py; P2: at the corners and edge
midpoints of the straight-edged mesh, as 6-node triangles).  Exit
status 3 when Newton did not converge (the outputs are written all the same).
The CPU time spent writing OUT.vtk goes to OUT.vtk.cpu.
"""
import sys
import time

import numpy as np

import getfem as gf
from field_vtk import write_vtk
from hertz_err import write_profile
from msh22 import read_msh

E, NU, DELTA = 200000.0, 0.3, 0.01
BOTTOM, BTOP = 1, 3        # block physical tags
ARC, DTOP = 1, 2           # disk physical tags


def main():
    bfile, dfile, out = sys.argv[1:4]
    max_res = float(sys.argv[4]) if len(sys.argv) > 4 else 1e-5
    max_iter = int(sys.argv[5]) if len(sys.argv) > 5 else 50
    degree = int(sys.argv[6]) if len(sys.argv) > 6 else 1
    vtk = sys.argv[7] if len(sys.argv) > 7 else None
    bmesh, dmesh = read_msh(bfile), read_msh(dfile)
    gf.util("trace level", 0)
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    mu = E / (2 * (1 + NU))
    m1 = gf.Mesh("import", "gmsh", bfile)
    m2 = gf.Mesh("import", "gmsh", dfile)
    mf1 = gf.MeshFem(m1, 2)
    mf1.set_classical_fem(degree)
    mf2 = gf.MeshFem(m2, 2)
    mf2.set_classical_fem(degree)
    mim1 = gf.MeshIm(m1, 2 * degree)
    mim2 = gf.MeshIm(m2, 2 * degree)
    md = gf.Model("real")
    md.add_fem_variable("u1", mf1)
    md.add_fem_variable("u2", mf2)
    md.add_initialized_data("clambda", [lam])
    md.add_initialized_data("cmu", [mu])
    md.add_isotropic_linearized_elasticity_brick(mim1, "u1", "clambda", "cmu")
    md.add_isotropic_linearized_elasticity_brick(mim2, "u2", "clambda", "cmu")
    # Multipliers, not "with simplification": the latter costs O(n^2) here.
    md.add_Dirichlet_condition_with_multipliers(mim1, "u1", 1, BOTTOM)
    md.add_initialized_data("DU", [0.0, -DELTA])
    md.add_Dirichlet_condition_with_multipliers(mim2, "u2", 1, DTOP, "DU")
    md.add_initialized_data("r", [E])
    md.add_nodal_contact_between_nonmatching_meshes_brick(mim1, mim2, "u1", "u2", "lambda_n", "r",
                                                          BTOP, ARC, 1, 0, 1)
    nit, conv = md.solve("max_res", max_res, "max_iter", max_iter, "lsolver", "mumps")
    P = abs(gf.asm_generic(mim2, 0, "mult_on_u2", DTOP, md)[1])
    dofs = mf1.basic_dof_on_region(BTOP)
    x = mf1.basic_dof_nodes(dofs[::2])[0]          # lambda_n follows these nodes
    order = np.argsort(x)
    xs = x[order]
    force = -md.variable("lambda_n")[order]
    w = np.zeros_like(xs)
    if degree == 1:
        w[:-1] += 0.5 * np.diff(xs)
        w[1:] += 0.5 * np.diff(xs)
    else:                                   # corners at even positions of the whole top line
        h = xs[2::2] - xs[:-2:2]
        w[:-2:2] += h / 6.0
        w[2::2] += h / 6.0
        w[1::2] = 2.0 * h / 3.0
    write_profile(out, list(xs), list(force / w), P=float(P), dofs=mf1.nbdof() + mf2.nbdof(),
                  newton_iterations=int(nit), converged=int(conv), order=degree)
    if vtk is not None:
        t_vtk = time.process_time()
        parts = []
        for (nodes, tris, _), mf, name in ((bmesh, mf1, "u1"), (dmesh, mf2, "u2")):
            u = md.variable(name)
            xy = mf.basic_dof_nodes()
            at = {(round(xy[0, k], 9), round(xy[1, k], 9)): (u[k], u[k + 1]) for k in range(0, mf.nbdof(), 2)}
            if degree == 2:             # the straight-edged mesh: the P2 dofs at the corners and edge midpoints
                nodes, tris6 = dict(nodes), []
                for t in tris:
                    mids = []
                    for i, j in ((0, 1), (1, 2), (2, 0)):
                        key = (min(t[i], t[j]), max(t[i], t[j]))
                        nodes.setdefault(key, tuple(0.5 * (nodes[t[i]][d] + nodes[t[j]][d]) for d in (0, 1)))
                        mids.append(key)
                    tris6.append(tuple(t[:3]) + tuple(mids))
                tris = tris6
            used = {n for t in tris for n in t}
            parts.append((nodes, tris, {n: at[round(nodes[n][0], 9), round(nodes[n][1], 9)] for n in used}))
        write_vtk(vtk, parts, degree)
        with open(vtk + ".cpu", "w") as f:             # the driver does not count this in the solve's time
            f.write(f"{time.process_time() - t_vtk!r}\n")
    return 0 if conv else 3


if __name__ == "__main__":
    sys.exit(main())
