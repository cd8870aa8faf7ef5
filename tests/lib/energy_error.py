"""The true energy-norm error of a contact2d run against an exact displacement
field, integrated over the run's own cells from its VTK file (standard
library only).  Independent of the program: the shape functions, the
quadrature and the elasticity are written here again, from the textbook.

    estimate(summary_path, what[, pair]) -> the value of `estimate WHAT [PAIR] VALUE`
    energy_error(vtk_path, exact, materials, kind="strain")
        -> (error, norm): ||u_exact - u_h||_E and ||u_exact||_E over every cell,
    ||v||_E^2 = int eps(v) : D eps(v) dV, dV = dA (plane, per unit thickness)
    or 2 pi r dA (kind="axisymmetric": x = r, y = z, the hoop strain u_r / r).

exact(x, y, body) returns (ux, uy, dux/dx, dux/dy, duy/dx, duy/dy) in body
body (1, 2, ...: the VTK's CELL_DATA body); materials[body - 1] is its
(E, nu), the last one serving the bodies after it.  Cells: 3- and 6-node
triangles, 4-, 8- and 9-node quadrilaterals in gmsh's and VTK's node order
(corners counter-clockwise, then mid-sides, then the centre), mapped
isoparametrically."""
import math

from c2dcheck import vtk

# Gauss rules: the triangle (area 1/2), Dunavant's 7 points, degree 5;
# the square [-1, 1]^2, 4 x 4 points, degree 7 in each variable.
_A, _B = 0.059715871789770, 0.470142064105115
_C, _D = 0.797426985353087, 0.101286507323456
TRI = [((1 / 3, 1 / 3), 0.225)] + \
      [((p, q), 0.132394152788506) for p, q in ((_B, _B), (_A, _B), (_B, _A))] + \
      [((p, q), 0.125939180544827) for p, q in ((_D, _D), (_C, _D), (_D, _C))]
TRI = [(xi, w / 2) for xi, w in TRI]
_G = [(-0.861136311594053, 0.347854845137454), (-0.339981043584856, 0.652145154862546),
      (0.339981043584856, 0.652145154862546), (0.861136311594053, 0.347854845137454)]
QUAD = [((s, t), ws * wt) for s, ws in _G for t, wt in _G]
QS = [-1, 1, 1, -1, 0, 1, 0, -1, 0]
QT = [-1, -1, 1, 1, -1, 0, 1, 0, 0]


def shape(nen, s, t):
    """Shape functions and their reference derivatives at (s, t)."""
    if nen == 3:
        return [1 - s - t, s, t], [(-1, -1), (1, 0), (0, 1)]
    if nen == 6:
        lam = [1 - s - t, s, t]
        dl = [(-1, -1), (1, 0), (0, 1)]
        n, d = [0.0] * 6, [(0.0, 0.0)] * 6
        for i in range(3):
            j = (i + 1) % 3
            n[i] = lam[i] * (2 * lam[i] - 1)
            d[i] = tuple((4 * lam[i] - 1) * c for c in dl[i])
            n[3 + i] = 4 * lam[i] * lam[j]
            d[3 + i] = tuple(4 * (lam[j] * dl[i][k] + lam[i] * dl[j][k]) for k in range(2))
        return n, d
    if nen == 4:
        n = [0.25 * (1 + s * QS[a]) * (1 + t * QT[a]) for a in range(4)]
        d = [(0.25 * QS[a] * (1 + t * QT[a]), 0.25 * QT[a] * (1 + s * QS[a])) for a in range(4)]
        return n, d
    if nen == 8:
        n, d = [], []
        for a in range(4):
            sa, ta = QS[a], QT[a]
            n.append(0.25 * (1 + s * sa) * (1 + t * ta) * (s * sa + t * ta - 1))
            d.append((0.25 * sa * (1 + t * ta) * (2 * s * sa + t * ta), 0.25 * ta * (1 + s * sa) * (s * sa + 2 * t * ta)))
        for a in range(4, 8):
            sa, ta = QS[a], QT[a]
            if sa == 0:
                n.append(0.5 * (1 - s * s) * (1 + t * ta)); d.append((-s * (1 + t * ta), 0.5 * (1 - s * s) * ta))
            else:
                n.append(0.5 * (1 + s * sa) * (1 - t * t)); d.append((0.5 * sa * (1 - t * t), -t * (1 + s * sa)))
        return n, d
    l1 = lambda x: [0.5 * x * (x - 1), 1 - x * x, 0.5 * x * (x + 1)]
    d1 = lambda x: [x - 0.5, -2 * x, x + 0.5]
    ls, lt, ds, dt = l1(s), l1(t), d1(s), d1(t)
    n = [ls[QS[a] + 1] * lt[QT[a] + 1] for a in range(9)]
    d = [(ds[QS[a] + 1] * lt[QT[a] + 1], ls[QS[a] + 1] * dt[QT[a] + 1]) for a in range(9)]
    return n, d


def estimate(summary_path, what, pair=None):
    """The value of the summary line `estimate WHAT [PAIR] VALUE` (None: absent)."""
    with open(summary_path) as h:
        for line in h:
            w = line.split()
            if len(w) >= 3 and w[0] == "estimate" and w[1] == what:
                if pair is None:
                    return float(w[2])
                if len(w) >= 4 and w[2] == str(pair):
                    return float(w[3])
    return None


def law(e, nu, kind):
    """D: (3 x 3) plane strain or stress, (4 x 4) axisymmetric (rr, zz, rz, tt)."""
    lam, mu = e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))
    if kind == "stress":
        lam = 2 * lam * mu / (lam + 2 * mu)
    if kind == "axisymmetric":
        return [[lam + 2 * mu, lam, 0, lam], [lam, lam + 2 * mu, 0, lam], [0, 0, mu, 0], [lam, lam, 0, lam + 2 * mu]]
    return [[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]]


def energy_error(vtk_path, exact, materials, kind="strain"):
    v = vtk(vtk_path)
    pts, u = v["points"], v["point"]["displacement"]
    body = v["cell"]["body"]
    axi = kind == "axisymmetric"
    err2 = norm2 = 0.0
    for c, cell in enumerate(v["cells"]):
        nen = len(cell)
        nb = int(body[c][0])
        d = law(*materials[min(nb, len(materials)) - 1], kind)
        for (s, t), w in (TRI if nen in (3, 6) else QUAD):
            n, dn = shape(nen, s, t)
            x = sum(n[a] * pts[cell[a]][0] for a in range(nen))
            y = sum(n[a] * pts[cell[a]][1] for a in range(nen))
            j11 = sum(dn[a][0] * pts[cell[a]][0] for a in range(nen))
            j12 = sum(dn[a][1] * pts[cell[a]][0] for a in range(nen))
            j21 = sum(dn[a][0] * pts[cell[a]][1] for a in range(nen))
            j22 = sum(dn[a][1] * pts[cell[a]][1] for a in range(nen))
            det = j11 * j22 - j12 * j21
            # dN/dx = (dN/ds J22 - dN/dt J21) / det, dN/dy = (-dN/ds J12 + dN/dt J11) / det
            gx = [(dn[a][0] * j22 - dn[a][1] * j21) / det for a in range(nen)]
            gy = [(-dn[a][0] * j12 + dn[a][1] * j11) / det for a in range(nen)]
            ux = sum(n[a] * u[cell[a]][0] for a in range(nen))
            uxx = sum(gx[a] * u[cell[a]][0] for a in range(nen))
            uxy = sum(gy[a] * u[cell[a]][0] for a in range(nen))
            uyx = sum(gx[a] * u[cell[a]][1] for a in range(nen))
            uyy = sum(gy[a] * u[cell[a]][1] for a in range(nen))
            ex, _, exx, exy, eyx, eyy = exact(x, y, nb)
            eps_ex = [exx, eyy, exy + eyx]
            eps_h = [uxx, uyy, uxy + uyx]
            if axi:
                eps_ex.append(ex / x)
                eps_h.append(ux / x)
            diff = [a - b for a, b in zip(eps_ex, eps_h)]
            dv = w * abs(det) * (2 * math.pi * x if axi else 1.0)
            k = len(diff)
            err2 += dv * sum(diff[i] * d[i][j] * diff[j] for i in range(k) for j in range(k))
            norm2 += dv * sum(eps_ex[i] * d[i][j] * eps_ex[j] for i in range(k) for j in range(k))
    return math.sqrt(err2), math.sqrt(norm2)
