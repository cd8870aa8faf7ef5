#!/usr/bin/python3
"""Energy-norm (and broken H1) error of a displacement field against a
reference field of the same problem, for P1 and P2 triangles (3- and 6-node,
curved isoparametric edges kept), over a window around the contact zone.

    h1_err.py [--window x0,x1,y0,y1] [-m E,nu] REF.vtk RUN.vtk...
        prints 'file h1_rel energy_rel' per run
    h1_err.py --self-test                 closed-form checks (PASS/FAIL lines)

Fields are legacy ASCII VTK files in contact2d's layout (POINTS, CELLS of VTK
type 5 or 22, POINT_DATA VECTORS displacement, CELL_DATA SCALARS body), as
contact2d writes them and field_vtk.py writes the peers' fields.  With
e = u_ref - u_h on each body,

    ||e||_E^2 = sum_B int sigma(e) : eps(e),   |e|_1^2 = sum_B int |grad e|^2,

both relative to the reference's own norms over the same region: the run's
triangles whose centroid lies in the window, each split into 4 and
integrated by the 6-point degree-4 rule on each quarter (24 points per
triangle, the run's isoparametric map).  grad u_h is a polynomial on each run
triangle (straight edges: of degree 0 for P1, 1 for P2), so the rule is exact
for the run's part; grad u_ref is evaluated at each point in the reference
triangle that contains it (found through a k-d tree of the reference's
centroids, its local coordinates by Newton on the isoparametric map), so the
only quadrature error is that of the reference's own kinks inside a run
triangle: the reference is much finer, and its gradient jumps are its own
discretisation error.  A point outside the reference body (a P2 run's curved
edge against the reference's, both on the circle to O(h^3)) takes the nearest
reference triangle's polynomial.  Plane strain, E = 200000, nu = 0.3 unless
-m says otherwise (the Hertz problem H).

This is the quadratic-capable counterpart of studies/c2dh1.f90 (P1 fields,
exact intersection of the meshes), for the bench's references, which are P2.
"""
import math
import os
import sys

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ref_err import Checks  # noqa: E402

# 6-point degree-4 rule on the unit triangle (Dunavant), weights summing to 1/2
_A, _B = 0.445948490915965, 0.091576213509771
_WA, _WB = 0.223381589678011 / 2.0, 0.109951743655322 / 2.0
RULE = np.array([[_A, _A, _WA], [1 - 2 * _A, _A, _WA], [_A, 1 - 2 * _A, _WA],
                 [_B, _B, _WB], [1 - 2 * _B, _B, _WB], [_B, 1 - 2 * _B, _WB]])


def _quarter_rule():
    """The rule on the 4 quarters of the unit triangle: (points (n, 2), weights (n,))."""
    pts, wts = [], []
    for (ox, oy, s) in ((0.0, 0.0, 0.5), (0.5, 0.0, 0.5), (0.0, 0.5, 0.5)):
        pts.append(np.c_[ox + s * RULE[:, 0], oy + s * RULE[:, 1]])
        wts.append(RULE[:, 2] * s * s)
    # the middle quarter, vertices (0.5, 0), (0, 0.5), (0.5, 0.5)
    v0, v1, v2 = np.array([0.5, 0.0]), np.array([0.0, 0.5]), np.array([0.5, 0.5])
    l1, l2 = RULE[:, 0:1], RULE[:, 1:2]
    pts.append(v0 + l1 * (v1 - v0) + l2 * (v2 - v0))
    wts.append(RULE[:, 2] * 0.25)
    return np.vstack(pts), np.concatenate(wts)


QPTS, QWTS = _quarter_rule()


def shape(xi, eta, nn):
    """Shape functions (m, nn) and their derivatives d/dxi, d/deta (m, nn) at points (xi, eta) of the unit
    triangle; nn = 3 (P1) or 6 (P2, corners then the midside nodes 12, 23, 31: gmsh's and VTK's order)."""
    xi, eta = np.asarray(xi, float), np.asarray(eta, float)
    l0 = 1.0 - xi - eta
    if nn == 3:
        n = np.stack([l0, xi, eta], -1)
        one = np.ones_like(xi)
        dx = np.stack([-one, one, 0 * one], -1)
        de = np.stack([-one, 0 * one, one], -1)
        return n, dx, de
    n = np.stack([l0 * (2 * l0 - 1), xi * (2 * xi - 1), eta * (2 * eta - 1), 4 * l0 * xi, 4 * xi * eta,
                  4 * eta * l0], -1)
    dx = np.stack([1 - 4 * l0, 4 * xi - 1, 0 * xi, 4 * (l0 - xi), 4 * eta, -4 * eta], -1)
    de = np.stack([1 - 4 * l0, 0 * xi, 4 * eta - 1, -4 * xi, 4 * xi, 4 * (l0 - eta)], -1)
    return n, dx, de


class Field:
    """A displacement field on triangles read from a VTK file: x (np, 2), u (np, 2), cells (nc, nn), body (nc,)."""

    def __init__(self, path=None, x=None, u=None, cells=None, body=None):
        if path is not None:
            x, u, cells, body = read_vtk(path)
        self.x, self.u, self.cells, self.body = np.asarray(x, float), np.asarray(u, float), \
            np.asarray(cells, int), np.asarray(body, int)
        self.nn = self.cells.shape[1]

    def bodies(self):
        return sorted(set(self.body.tolist()))

    def locator(self, b):
        """The Locator of body b's triangles, built once per field."""
        if not hasattr(self, "_locators"):
            self._locators = {}
        if b not in self._locators:
            self._locators[b] = Locator(self, np.nonzero(self.body == b)[0])
        return self._locators[b]


def read_vtk(path):
    """(x, u, cells, body) of a legacy ASCII VTK file with one kind of triangle (type 5 or 22)."""
    with open(path) as f:
        lines = f.read().split("\n")
    x = u = cells = body = None
    k = 0
    while k < len(lines):
        w = lines[k].split()
        if not w:
            k += 1
            continue
        if w[0] == "POINTS":
            n = int(w[1])
            x = np.array(" ".join(lines[k + 1:k + 1 + n]).split(), float).reshape(n, 3)[:, :2]
            k += 1 + n
        elif w[0] == "CELLS":
            n = int(w[1])
            rows = [r.split() for r in lines[k + 1:k + 1 + n]]
            nn = int(rows[0][0])
            if any(int(r[0]) != nn for r in rows) or nn not in (3, 6):
                raise ValueError(f"{path}: cells of 3 or of 6 nodes expected, one kind")
            cells = np.array([r[1:] for r in rows], int)
            k += 1 + n
        elif w[0] == "POINT_DATA":
            k += 1
            while k < len(lines) and not lines[k].startswith("CELL_DATA"):
                w2 = lines[k].split()
                if w2[:2] == ["VECTORS", "displacement"]:
                    u = np.array(" ".join(lines[k + 1:k + 1 + len(x)]).split(), float).reshape(len(x), 3)[:, :2]
                    k += len(x)
                k += 1
        elif w[0] == "CELL_DATA":
            k += 1
            while k < len(lines):
                w2 = lines[k].split()
                if w2[:2] == ["SCALARS", "body"]:
                    body = np.array(" ".join(lines[k + 2:k + 2 + len(cells)]).split(), int)
                    break
                k += 1
            break
        else:
            k += 1
    if x is None or u is None or cells is None or body is None:
        raise ValueError(f"{path}: POINTS, CELLS, displacement and body expected")
    return x, u, cells, body


def lame(e, nu):
    """Plane-strain Lame constants."""
    return e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))


def _grad(fld, idx, xi, eta):
    """Points x (m, 2), displacement gradient g (m, 2, 2) [i, j] = du_i/dx_j and det J (m,) of the cells idx
    (m,) at local points (xi, eta) (m,) each."""
    n, dx, de = shape(xi, eta, fld.nn)
    xe = fld.x[fld.cells[idx]]                      # (m, nn, 2)
    ue = fld.u[fld.cells[idx]]
    pos = np.einsum("mk,mkd->md", n, xe)
    j = np.stack([np.einsum("mk,mkd->md", dx, xe), np.einsum("mk,mkd->md", de, xe)], -1)   # j[m, d, r]
    det = j[:, 0, 0] * j[:, 1, 1] - j[:, 0, 1] * j[:, 1, 0]
    inv = np.stack([np.stack([j[:, 1, 1], -j[:, 0, 1]], -1), np.stack([-j[:, 1, 0], j[:, 0, 0]], -1)], -2) \
        / det[:, None, None]                        # inv[m, r, d] = d xi_r / d x_d
    du = np.stack([np.einsum("mk,mki->mi", dx, ue), np.einsum("mk,mki->mi", de, ue)], -1)   # du[m, i, r]
    return pos, np.einsum("mir,mrd->mid", du, inv), det


class Locator:
    """The reference triangle containing each point, and the point's local coordinates, for one body."""

    def __init__(self, fld, cells):
        self.fld, self.cells = fld, cells
        c = fld.x[fld.cells[cells, :3]]             # corners (nc, 3, 2)
        self.c0 = c[:, 0]
        m = np.stack([c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]], -1)   # m[k, d, r]
        det = m[:, 0, 0] * m[:, 1, 1] - m[:, 0, 1] * m[:, 1, 0]
        self.minv = np.stack([np.stack([m[:, 1, 1], -m[:, 0, 1]], -1),
                              np.stack([-m[:, 1, 0], m[:, 0, 0]], -1)], -2) / det[:, None, None]
        self.tree = cKDTree(c.mean(axis=1))

    def locate(self, p, k=16):
        """(cell index into the field's cells, xi, eta) of points p (m, 2)."""
        _, cand = self.tree.query(p, k=min(k, len(self.cells)))
        cand = cand.reshape(len(p), -1)
        best = np.full(len(p), -1)
        bestmin = np.full(len(p), -np.inf)
        bxi = np.zeros(len(p))
        beta = np.zeros(len(p))
        todo = np.arange(len(p))
        for j in range(cand.shape[1]):             # nearest centroids first; a point found inside is done
            cj = cand[todo, j]
            lam = np.einsum("mrd,md->mr", self.minv[cj], p[todo] - self.c0[cj])
            mn = np.minimum(np.minimum(lam[:, 0], lam[:, 1]), 1 - lam[:, 0] - lam[:, 1])
            take = mn > bestmin[todo] + 1e-14
            t = todo[take]
            best[t], bestmin[t], bxi[t], beta[t] = cj[take], mn[take], lam[take, 0], lam[take, 1]
            todo = todo[bestmin[todo] < 0.0]
            if len(todo) == 0:
                break
        cell = self.cells[best]
        if self.fld.nn == 6:                        # Newton on the isoparametric map (curved edges)
            for _ in range(6):
                n, dx, de = shape(bxi, beta, 6)
                xe = self.fld.x[self.fld.cells[cell]]
                r = p - np.einsum("mk,mkd->md", n, xe)
                j = np.stack([np.einsum("mk,mkd->md", dx, xe), np.einsum("mk,mkd->md", de, xe)], -1)
                det = j[:, 0, 0] * j[:, 1, 1] - j[:, 0, 1] * j[:, 1, 0]
                bxi = bxi + (j[:, 1, 1] * r[:, 0] - j[:, 0, 1] * r[:, 1]) / det
                beta = beta + (-j[:, 1, 0] * r[:, 0] + j[:, 0, 0] * r[:, 1]) / det
        return cell, bxi, beta


def energy_errors(ref, run, window=None, e=200000.0, nu=0.3):
    """(|e|_1 / |u_ref|_1, ||e||_E / ||u_ref||_E) over the run's cells with centroid in window (x0, x1, y0, y1)."""
    lam, mu = lame(e, nu)
    num1 = den1 = nume = dene = 0.0
    q = len(QWTS)
    for b in run.bodies():
        rc = np.nonzero(run.body == b)[0]
        cen = run.x[run.cells[rc, :3]].mean(axis=1)
        if window is not None:
            x0, x1, y0, y1 = window
            rc = rc[(cen[:, 0] >= x0) & (cen[:, 0] <= x1) & (cen[:, 1] >= y0) & (cen[:, 1] <= y1)]
        if len(rc) == 0:
            continue
        loc = ref.locator(b)
        for s in range(0, len(rc), 20000):          # in chunks: memory
            cc = np.repeat(rc[s:s + 20000], q)
            xi = np.tile(QPTS[:, 0], len(cc) // q)
            eta = np.tile(QPTS[:, 1], len(cc) // q)
            w = np.tile(QWTS, len(cc) // q)
            pos, gh, det = _grad(run, cc, xi, eta)
            w = w * np.abs(det)
            rcell, rxi, reta = loc.locate(pos)
            _, gr, _ = _grad(ref, rcell, rxi, reta)
            for g, sign in ((gr - gh, 0), (gr, 1)):
                exx, eyy, gxy = g[:, 0, 0], g[:, 1, 1], g[:, 0, 1] + g[:, 1, 0]
                en = lam * (exx + eyy) ** 2 + 2 * mu * (exx ** 2 + eyy ** 2) + mu * gxy ** 2
                h1 = (g ** 2).sum(axis=(1, 2))
                if sign == 0:
                    nume += float(w @ en)
                    num1 += float(w @ h1)
                else:
                    dene += float(w @ en)
                    den1 += float(w @ h1)
    return math.sqrt(num1 / den1), math.sqrt(nume / dene)


def _mesh(n, order, curve=0.0):
    """A mesh of [0, 1]^2 with 2 n^2 triangles of the given order; with curve != 0 the whole square is mapped
    by (x, y) -> (x, y + curve x (1 - x)), so that the P2 mesh's edges are curved."""
    k = order * n + 1
    ij = [(i, j) for j in range(k) for i in range(k)]
    x = np.array([[i / (k - 1), j / (k - 1)] for i, j in ij])
    x[:, 1] += curve * x[:, 0] * (1 - x[:, 0])
    idx = lambda i, j: j * k + i   # noqa: E731
    cells = []
    for j in range(n):
        for i in range(n):
            a, b = order * i, order * j
            if order == 1:
                cells += [[idx(a, b), idx(a + 1, b), idx(a + 1, b + 1)], [idx(a, b), idx(a + 1, b + 1), idx(a, b + 1)]]
            else:
                cells += [[idx(a, b), idx(a + 2, b), idx(a + 2, b + 2), idx(a + 1, b), idx(a + 2, b + 1), idx(a + 1, b + 1)],
                          [idx(a, b), idx(a + 2, b + 2), idx(a, b + 2), idx(a + 1, b + 1), idx(a + 1, b + 2), idx(a, b + 1)]]
    return x, np.array(cells)


def self_test():
    """Closed-form checks; returns the number of failures."""
    check = Checks()

    # 1. u = (x^2, x^2 - 3 y + x), in the isoparametric P2 space of both meshes (x is affine in the local
    #    coordinates of both, y is the coordinate itself): error 0 to round-off, the reference's edges curved
    f = lambda x: np.c_[x[:, 0] ** 2, x[:, 0] ** 2 - 3 * x[:, 1] + x[:, 0]]   # noqa: E731
    xr, cr = _mesh(7, 2, curve=0.1)
    ref = Field(x=xr, u=f(xr), cells=cr, body=np.ones(len(cr), int))
    xh, ch = _mesh(3, 2)
    run = Field(x=xh, u=f(xh), cells=ch, body=np.ones(len(ch), int))
    # run's square [0,1]^2 vs the reference's curved domain: compare on a window inside both
    h1, en = energy_errors(ref, run, window=(0.0, 1.0, 0.3, 1.0))
    check(h1 < 1e-10 and en < 1e-10, "h1_err: a quadratic field on two P2 meshes (one curved) agrees",
          f"{h1!r} {en!r}")
    # 2. P1 run of u = (x^2, 0) on n x n squares: grad u_h = (x_i + x_{i+1}, 0) on the column [x_i, x_{i+1}];
    #    int (2x - x_i - x_{i+1})^2 = h^3/3 per column, h^2/3 in all; |u|_1^2 = int 4 x^2 = 4/3: rel = h/2
    g = lambda x: np.c_[x[:, 0] ** 2, 0 * x[:, 0]]   # noqa: E731
    xr, cr = _mesh(4, 2)
    ref = Field(x=xr, u=g(xr), cells=cr, body=np.ones(len(cr), int))
    for n in (2, 5):
        x1, c1 = _mesh(n, 1)
        run = Field(x=x1, u=g(x1), cells=c1, body=np.ones(len(c1), int))
        h1, _ = energy_errors(ref, run)
        want = (1.0 / n) / 2.0
        check(abs(h1 - want) <= 1e-10 * want, f"h1_err: P1 interpolant of x^2, n = {n}", f"{h1!r} != {want!r}")
    return check.fails


def main(argv):
    if argv[1:2] == ["--self-test"]:
        return 1 if self_test() else 0
    window, e, nu, files = None, 200000.0, 0.3, []
    k = 1
    while k < len(argv):
        if argv[k] == "--window":
            window = tuple(float(v) for v in argv[k + 1].split(","))
            k += 2
        elif argv[k] == "-m":
            e, nu = (float(v) for v in argv[k + 1].split(","))
            k += 2
        else:
            files.append(argv[k])
            k += 1
    if len(files) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    ref = Field(files[0])
    for fn in files[1:]:
        h1, en = energy_errors(ref, Field(fn), window, e, nu)
        print(f"{fn} {h1:.6e} {en:.6e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
