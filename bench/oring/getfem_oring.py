#!/usr/bin/python3
"""GetFEM 5.4 reference for a plane-strain neo-Hookean O-ring squeezed between two plates.

    getfem_oring.py MESH.msh DEGREE OUT.txt [SQUEEZE,SQUEEZE,...]

Cross-section diameter d = 5 (radius R = 2.5, mm), W = mu/2 (J^(-2/3) I1 - 3)
+ K/2 (J - 1)^2 with I1 = tr(F^T F) of the 3D gradient, F33 = 1 (plane
strain: I1 = |F_2D|^2 + 1, J = det F_2D), mu = 1, K = 1000 (MPa).  The quarter
x >= 0, y >= 0 of the section (gmsh mesh of oring_quarter.geo, physical tags:
arc 1, x = 0 2, y = 0 3) with ux = 0 on x = 0 and uy = 0 on y = 0; the rigid
frictionless plate y = R - squeeze d / 2 above it.  The squeezes (default
0.01,0.05,0.10,0.15,0.20,0.25,0.30) are load steps, each solved by Newton
from the previous one's solution.

Formulation (why): K/mu = 1000 (nu = 0.4995): pure-displacement triangles
lock.  A mixed u-p (perturbed Lagrangian) form of the same energy,
    Pi(u, p) = int mu/2 (J^(-2/3) I1 - 3) + p (J - 1) - p^2 / (2 K),
whose stationary point with p = K (J - 1) is that of W.  DEGREE 2: u P2,
p continuous P1 (Taylor-Hood, inf-sup stable: the reference).  DEGREE 1:
u P1, p P0 (not inf-sup stable, its pressure oscillates; GetFEM's cheapest
series for cost comparisons only; MINI is stable but the nodal contact brick
takes pure Lagrange fems only).  The first Piola stress mu J^(-2/3) (F - I1/3 F^-T)
+ p J F^-T is written in GetFEM's weak-form language; GetFEM derives the
tangent (exact Newton).  Meshes: DEGREE 2 reads the second-order
(curved-edge) gmsh mesh, DEGREE 1 the straight one.

Contact: GetFEM's nodal contact with a rigid obstacle
(add_nodal_contact_with_rigid_obstacle_brick, signed distance R - y,
non-symmetric Alart-Curnier augmented Lagrangian, r = 3 ~ E), frictionless,
on the arc's nodes.  The plate stays at y = R and the squeeze moves the
y = 0 symmetry line up instead (the same solution up to a rigid
translation).  For a flat plate the linearised gap R - y - u_y is exact at
any sliding.  (The integral variant of the brick was left: its multiplier
oscillates near the edge, and it reads the obstacle field at the deformed
point, which leaves the mesh when the body moves up.)

Newton: full GetFEM tangent, MUMPS, a hand-written loop so that every
iteration's residual is printed; backtracking halves the step while the
residual grows (said in the output).  Converged: |r| <= 1e-9 (the residual's
force rows are in N/mm; the load is O(1) N/mm) and |du| <= 1e-10 d.

Outputs per squeeze (OUT.txt and stdout):
  F     force per unit length of the FULL ring on ONE plate = 2 x the quarter's
        plate reaction (the quarter holds half of the contact strip, x >= 0)
  Fsym  the reaction on the y = 0 symmetry line of the quarter, x 2 (equilibrium check)
  b     the contact half-width in the current configuration: the in-contact node
        furthest out (b_in) and the first free one (b_out) bracket it; b is the
        zero of gap^(2/3) extrapolated linearly from the first two free nodes
        (gap ~ (x - b)^(3/2) outside a smooth edge), clipped to the bracket
  pmax  the peak true (Cauchy) contact pressure: nominal stress / boundary
        stretch |F T| at the multiplier nodes (the centre, x = 0); pnom the nominal
  nit, residuals, cpu (process time of the step), Jmin over the quadrature points
"""
import sys
import time

import numpy as np

import getfem as gf

R, MU, KB = 2.5, 1.0, 1000.0
D = 2.0 * R
ARC, XSYM, YSYM = 1, 2, 3
STEPS = (0.01, 0.05, 0.10, 0.15, 0.20, 0.25, 0.30)
TOL_RES, TOL_DU, MAX_IT = 1e-9, 1e-10 * D, 40
RAUG = 3.0 * MU            # augmentation: about E (GetFEM's advice)


def build(mesh_file, degree):
    """The model: mesh, fems, variables, bricks."""
    m = gf.Mesh("import", "gmsh", mesh_file)
    mfu = gf.MeshFem(m, 2)
    if degree == 2:
        mfu.set_classical_fem(2)
    else:
        mfu.set_classical_fem(1)
    mfp = gf.MeshFem(m, 1)
    if degree == 2:
        mfp.set_classical_fem(1)
    else:
        mfp.set_classical_discontinuous_fem(0)
    mfl = gf.MeshFem(m, 1)                       # the symmetry conditions' multipliers
    mfl.set_classical_fem(1)
    mfj = gf.MeshFem(m, 1)                       # discontinuous: J at element nodes
    mfj.set_classical_discontinuous_fem(2)
    mim = gf.MeshIm(m, gf.Integ("IM_TRIANGLE(6)") if degree == 2 else gf.Integ("IM_TRIANGLE(4)"))
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_fem_variable("p", mfp)
    md.add_initialized_data("mu", [MU])
    md.add_initialized_data("K", [KB])
    md.add_macro("F", "(Id(2)+Grad_u)")
    md.add_macro("J", "Det(F)")
    md.add_nonlinear_term(mim, "(mu*pow(J,-2/3)*(F-(Norm_sqr(F)+1)/3*Inv(F)')"
                               "+p*J*Inv(F)'):Grad_Test_u + (J-1-p/K)*Test_p")
    # The plate stays at y = R; the squeeze moves the y = 0 symmetry line up by
    # squeeze d / 2 instead (a rigid translation of the same solution: strains,
    # forces and current x are those of the plate moving down).  Outward normal
    # of y = 0 is -e_y: u.n = -uy.
    md.add_initialized_data("uyn", [0.0])
    mx = md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mfl, XSYM)
    my = md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mfl, YSYM, "uyn")
    md.add_variable("lambda_n", len(mfu.basic_dof_on_region(ARC)) // 2)   # one nodal force per arc node
    md.add_initialized_data("r", [RAUG])
    md.add_nodal_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "r", ARC, f"{R!r}-y", 1)
    return dict(m=m, mfj=mfj, mfu=mfu, mfp=mfp, mim=mim, md=md,
                multx=md.mult_varname_Dirichlet(mx), multy=md.mult_varname_Dirichlet(my))


def newton(md, log):
    """Newton with backtracking; returns (iterations, residual history, converged)."""
    hist, dunorm = [], np.inf
    for it in range(MAX_IT + 1):
        md.assembly("build_all")
        rhs = md.rhs()
        res = float(np.linalg.norm(rhs))
        hist.append(res)
        if it > 0 and res <= TOL_RES and dunorm <= TOL_DU:
            return it, hist, True
        if it == MAX_IT:
            break
        du = np.asarray(gf.linsolve_mumps(md.tangent_matrix(), rhs)).ravel()
        x0 = md.from_variables()
        alpha = 1.0
        for _ in range(8):
            md.to_variables(x0 + alpha * du)
            md.assembly("build_rhs")
            rn = float(np.linalg.norm(md.rhs()))
            if np.isfinite(rn) and (rn < res or res < 1e3 * TOL_RES):
                break
            alpha *= 0.5
            log(f"    backtrack: alpha = {alpha:g} (|r| {rn:.3e} >= {res:.3e})")
        dunorm = alpha * float(np.linalg.norm(du))
        log(f"    it {it:2d}  |r| = {res:.3e}  |du| = {dunorm:.3e}  alpha = {alpha:g}")
    return MAX_IT, hist, False


def _weights(sl, degree):
    """Lumped weights (row sums of the trace mass matrix) of the boundary nodes
    at arc abscissae sl (sorted; P2: corners at even positions)."""
    w = np.zeros_like(sl)
    if degree == 1:
        w[:-1] += 0.5 * np.diff(sl)
        w[1:] += 0.5 * np.diff(sl)
    else:
        h = sl[2::2] - sl[:-2:2]
        w[:-2:2] += h / 6.0
        w[2::2] += h / 6.0
        w[1::2] = 2.0 * h / 3.0
    return w


def contact_profile(s, degree):
    """Contact profile on the arc sorted from the top point: current x,
    nominal and true pressure (nodal force over the lumped weight on the
    reference and on the current boundary), their ratio, and the gap to the
    plate y = R.  lambda_n follows the arc's u nodes in dof order."""
    md, mfu = s["md"], s["mfu"]
    u = md.variable("u")
    du = mfu.basic_dof_on_region(ARC)
    X = mfu.basic_dof_nodes(du[::2])
    f = -md.variable("lambda_n")                        # nodal forces, compressive positive
    order = np.argsort(np.arctan2(X[0], X[1]))
    X, f = X[:, order], f[order]
    xc = X[0] + u[du[::2]][order]
    yc = X[1] + u[du[1::2]][order]
    sref = R * np.arctan2(X[0], X[1])
    scur = np.concatenate(([0.0], np.cumsum(np.hypot(np.diff(xc), np.diff(yc)))))
    wref, wcur = _weights(sref, degree), _weights(scur, degree)
    return xc, f / wref, f / wcur, wref / wcur, R - yc


def half_width(xc, ptrue, gap, pmax):
    """(b, last in-contact x, first free x) from the profile sorted from the
    top point.  Outside a smooth contact edge the gap grows like (x - b)^(3/2)
    (Hertz): b is where the line through (x, gap^(2/3)) of the first two free
    nodes meets zero, clipped to the bracket (the p^2 extrapolation of the
    in-contact side is noisier with P2's lumped nodal pressures)."""
    on = np.nonzero(ptrue > 1e-9 * pmax)[0]
    k = on.max()
    x_in = xc[k]
    if k + 2 >= len(xc):
        return x_in, x_in, np.nan
    x_out = xc[k + 1]
    g1, g2 = gap[k + 1] ** (2.0 / 3.0), gap[k + 2] ** (2.0 / 3.0)
    if g2 > g1 > 0.0:
        b = xc[k + 1] - g1 * (xc[k + 2] - xc[k + 1]) / (g2 - g1)
    else:
        b = 0.5 * (x_in + x_out)
    return min(max(b, x_in), x_out), x_in, x_out


def main():
    mesh_file, degree, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    steps = [float(v) for v in sys.argv[4].split(",")] if len(sys.argv) > 4 and sys.argv[4] else list(STEPS)
    gf.util("trace level", 0)
    lines = []

    def log(msg):
        print(msg, flush=True)
        lines.append("# " + msg)

    t0 = time.process_time()
    s = build(mesh_file, degree)
    md = s["md"]
    ndof = md.nbdof()
    log(f"mesh {mesh_file} degree {degree} convexes {s['m'].nbcvs()} dofs {ndof} "
        f"(u {s['mfu'].nbdof()}, p {s['mfp'].nbdof()})  setup cpu {time.process_time() - t0:.2f} s")
    rows, ok_all = [], True
    for sq in steps:
        md.set_variable("uyn", [-sq * D / 2.0])
        t1 = time.process_time()
        log(f"step squeeze {sq:g}: approach of each plate {sq * D / 2.0:g}")
        nit, hist, ok = newton(md, log)
        cpu = time.process_time() - t1
        ok_all = ok_all and ok
        Fq = float(np.sum(-md.variable("lambda_n")))    # nodal contact forces of the quarter
        Fsym = abs(float(gf.asm_generic(s["mim"], 0, s["multy"], YSYM, md)))
        Jmin = float(np.min(md.interpolation("Det(Id(2)+Grad_u)", s["mfj"])))
        xc, pnom, ptrue, stretch, gap = contact_profile(s, degree)
        k0 = int(np.argmin(np.abs(xc)))
        pmax = float(np.max(ptrue))
        b, x_in, x_out = half_width(xc, ptrue, gap, pmax)
        row = dict(squeeze=sq, F=2.0 * Fq, Fsym=2.0 * Fsym, b=b, b_in=x_in, b_out=x_out,
                   pmax=pmax, pnom_max=float(np.max(pnom)), stretch0=float(stretch[k0]),
                   x_pmax=float(xc[int(np.argmax(ptrue))]), min_gap=float(np.min(gap[ptrue > 0]) if np.any(ptrue > 0) else np.nan),
                   Jmin=Jmin, nit=nit, converged=int(ok), cpu=cpu,
                   res=" ".join(f"{r:.2e}" for r in hist))
        rows.append(row)
        log(f"  squeeze {sq:g}: F = {row['F']:.6g} N/mm (symmetry line {row['Fsym']:.6g}), "
            f"b = {b:.5f} [{x_in:.5f}, {x_out:.5f}], pmax = {pmax:.5f} MPa at x = {row['x_pmax']:.4f} "
            f"(nominal {row['pnom_max']:.5f}), min gap {row['min_gap']:.2e}, Jmin {Jmin:.4f}, "
            f"Newton {nit} it {'converged' if ok else 'NOT CONVERGED'}, cpu {cpu:.2f} s")
        if not ok:
            break
    with open(out, "w") as f:
        for ln in lines:
            f.write(ln + "\n")
        f.write(f"# dofs {ndof}\n# degree {degree}\n# mesh {mesh_file}\n")
        keys = list(rows[0].keys()) if rows else []
        f.write("\t".join(keys) + "\n")
        for r in rows:
            f.write("\t".join(repr(r[k]) if isinstance(r[k], float) else str(r[k]) for k in keys) + "\n")
    log(f"total cpu {time.process_time() - t0:.2f} s")
    return 0 if ok_all else 3


if __name__ == "__main__":
    sys.exit(main())
