"""The true stress error of a B-bar run (a nearly incompressible body:
doc/theory.md, "Nearly incompressible materials") against an exact
displacement field, integrated over the run's own cells from its VTK file
(standard library only, independent of the program).

    bbar_error(vtk_path, exact, material, modes, kind="strain") -> (error, norm)

||sigma - sigma_h||_{D^-1} = ||eps(u) - eps_bar(u_h)||_D and ||eps(u)||_D over
every cell, eps_bar the strain of B-bar: the volumetric strain theta of u_h
(exx + eyy in plane strain, + u_r / r in axisymmetry) replaced on each cell
by its L2 projection onto modes[nen] polynomials (1: the mean; 3: 1, x, y),
the deviatoric part kept.  That is the error the stress of the solution
carries, the one its error estimate estimates; the energy norm of
u - u_h itself weighs div(u - u_h) by lambda, which B-bar leaves free
pointwise.  exact, material and kind as energy_error's (one body)."""
import math

from c2dcheck import vtk
from energy_error import TRI, QUAD, shape, law


def _points(pts, cell, u, axi):
    """Per quadrature point of cell: (weight dV, x, y, strain of u_h (3 or 4))."""
    nen = len(cell)
    out = []
    for (s, t), w in (TRI if nen in (3, 6) else QUAD):
        n, dn = shape(nen, s, t)
        x = sum(n[a] * pts[cell[a]][0] for a in range(nen))
        y = sum(n[a] * pts[cell[a]][1] for a in range(nen))
        j11 = sum(dn[a][0] * pts[cell[a]][0] for a in range(nen))
        j12 = sum(dn[a][1] * pts[cell[a]][0] for a in range(nen))
        j21 = sum(dn[a][0] * pts[cell[a]][1] for a in range(nen))
        j22 = sum(dn[a][1] * pts[cell[a]][1] for a in range(nen))
        det = j11 * j22 - j12 * j21
        gx = [(dn[a][0] * j22 - dn[a][1] * j21) / det for a in range(nen)]
        gy = [(-dn[a][0] * j12 + dn[a][1] * j11) / det for a in range(nen)]
        eps = [sum(gx[a] * u[cell[a]][0] for a in range(nen)), sum(gy[a] * u[cell[a]][1] for a in range(nen)),
               sum(gy[a] * u[cell[a]][0] + gx[a] * u[cell[a]][1] for a in range(nen))]
        if axi:
            eps.append(sum(n[a] * u[cell[a]][0] for a in range(nen)) / x)
        out.append((w * abs(det) * (2 * math.pi * x if axi else 1.0), x, y, eps))
    return out


def _solve(m, g):
    """m^-1 g for a small dense m (Gauss elimination with pivoting)."""
    k = len(g)
    a = [row[:] + [g[i]] for i, row in enumerate(m)]
    for c in range(k):
        p = max(range(c, k), key=lambda i: abs(a[i][c]))
        a[c], a[p] = a[p], a[c]
        for i in range(c + 1, k):
            f = a[i][c] / a[c][c]
            a[i] = [x - f * y for x, y in zip(a[i], a[c])]
    x = [0.0] * k
    for i in range(k - 1, -1, -1):
        x[i] = (a[i][k] - sum(a[i][j] * x[j] for j in range(i + 1, k))) / a[i][i]
    return x


def bbar_error(vtk_path, exact, material, modes, kind="strain"):
    v = vtk(vtk_path)
    pts, u = v["points"], v["point"]["displacement"]
    axi = kind == "axisymmetric"
    d = law(*material, kind)
    vol = [0, 1, 3] if axi else [0, 1]
    err2 = norm2 = 0.0
    for cell in v["cells"]:
        qp = _points(pts, cell, u, axi)
        npm = modes.get(len(cell), 0)
        if npm:
            # theta_bar = p' c, M c = int p theta dV, p = (1, x - xc, y - yc)[:npm]
            xc = sum(pts[k][0] for k in cell) / len(cell)
            yc = sum(pts[k][1] for k in cell) / len(cell)
            basis = lambda x, y: [1.0, x - xc, y - yc][:npm]
            m = [[sum(dv * basis(x, y)[i] * basis(x, y)[j] for dv, x, y, _ in qp) for j in range(npm)]
                 for i in range(npm)]
            g = [sum(dv * basis(x, y)[i] * sum(e[k] for k in vol) for dv, x, y, e in qp) for i in range(npm)]
            c = _solve(m, g)
        for dv, x, y, e in qp:
            if npm:
                dth = (sum(ci * pi for ci, pi in zip(c, basis(x, y))) - sum(e[k] for k in vol)) / len(vol)
                e = [ek + (dth if k in vol else 0.0) for k, ek in enumerate(e)]
            ex, _, exx, exy, eyx, eyy = exact(x, y, 1)
            eps_ex = [exx, eyy, exy + eyx] + ([ex / x] if axi else [])
            diff = [a - b for a, b in zip(eps_ex, e)]
            k = len(diff)
            err2 += dv * sum(diff[i] * d[i][j] * diff[j] for i in range(k) for j in range(k))
            norm2 += dv * sum(eps_ex[i] * d[i][j] * eps_ex[j] for i in range(k) for j in range(k))
    return math.sqrt(err2), math.sqrt(norm2)
