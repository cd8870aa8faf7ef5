#!/usr/bin/env python3
"""Error measures of contact2d runs against a fine reference (standard library only).

    c2derr.py h1 REF.vtk RUN.vtk [RUN.vtk ...] [-m E,nu ...] [--plane strain|stress]
                                               [--window x0,x1,y0,y1]
        Broken H1 seminorm and energy norm of u_ref - u_h, per body and in total:
            |e|_{1,h}^2 = sum_bodies int |grad(u_ref - u_h)|^2,
            ||e||_E^2   = sum_bodies int sigma(e) : eps(e).
        The integrals run over the reference mesh's cells (P1 triangles, Q1 quads);
        u_h is evaluated at the reference quadrature points by point location in
        the same body of the run's mesh (bucket grid) and barycentric (P1) or
        inverse-bilinear (Q1) interpolation.  A reference triangle lying inside
        one run triangle (nested meshes, e.g. MESH rect with nx multiplied) is
        integrated exactly with one point (both gradients are constant on it);
        any other reference triangle is clipped against the run triangles it
        meets and integrated exactly piece by piece (when the run mesh has Q1
        cells: with the centroids of its 16 pieces of a 4 x 4 split).  A part outside the run's
        body (a curved boundary meshed by chords) takes the gradient of the
        nearest run cell (its linear extension).  Q1 cells (either side) use
        2 x 2 Gauss points located one by one.  -m E,nu gives the material of body 1, 2, ... (the last one
        repeats); --window restricts the integrals to reference cells whose
        centroid lies in the box.  One CSV line per run:
            run,h1,h1_rel,energy,energy_rel,nested,h1_body1,h1_body2,...
        (h1_rel, energy_rel relative to the reference's own seminorm / energy
        norm over the same region; nested = share of reference triangles
        integrated exactly).

    c2derr.py pressure REF_contact.csv RUN_contact.csv [...] [--pair 1]
                                               [--xmin A] [--xmax B] [--axis x|y]
        Pressure on the slave boundary against the reference's profile, both
        taken piecewise linear between the slave nodes:
            p_l2   = ||p_h - p_ref||_{L2(A,B)} / ||p_ref||_{L2(A,B)}   (exact integral
                     on the merged breakpoints; A, B default to the whole range)
            F_l2, F_max: the resultant distribution F(x) = int_x^end p ds, its L2
                     difference over the whole boundary relative to F_ref(start) times
                     the boundary length^(1/2), and its largest difference relative to
                     F_ref(start).
        One CSV line per run: run,p_l2,F_l2,F_max.

    c2derr.py hertz RUN_contact.csv RUN.summary [...] --E E --nu nu --R R
                                               [--load disk:top]
        Hertz measures (cylinder on a half-space, plane strain, per unit length)
        with the computed load P = |Fy| of the reaction on the load boundary:
            1/E* = 2 (1 - nu^2) / E,  a = sqrt(4 P R / (pi E*)),  p0 = 2 P / (pi a),
        a_h from the pressure's second moment, a_h^2 = 4 int p x^2 / int p,
        p0_h = max nodal pressure, and the L2 difference over |x| < a of the
        piecewise linear p_h against p0 sqrt(1 - x^2 / a^2) (exact integral of
        the linear part, 8-point Gauss of the square root on each piece).
        One CSV line per pair of files: run,P,a,p0,a_h,p0_h,a_err,p0_err,p_l2.
"""
import math
import sys


# ----------------------------------------------------------------------------- reading

def _take(f, count, conv):
    """Read whitespace-separated tokens from f until count of them, converted."""
    out = []
    while len(out) < count:
        line = f.readline()
        if not line:
            raise ValueError("unexpected end of file")
        out.extend(map(conv, line.split()))
    return out


def read_vtk(path):
    """Points (xs, ys), cells (list of vertex tuples), cell types, displacement
    (ux, uy) and the cell array `body` of a legacy ASCII VTK file from contact2d."""
    xs = ys = cells = types = ux = uy = body = None
    section = None
    count = 0
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                break
            w = line.split()
            if not w:
                continue
            key = w[0].upper()
            if key == "POINTS":
                n = int(w[1])
                v = _take(f, 3 * n, float)
                xs, ys = v[0::3], v[1::3]
            elif key == "CELLS":
                n, size = int(w[1]), int(w[2])
                v = _take(f, size, int)
                cells = []
                i = 0
                for _ in range(n):
                    m = v[i]
                    cells.append(tuple(v[i + 1:i + 1 + m]))
                    i += 1 + m
            elif key == "CELL_TYPES":
                types = _take(f, int(w[1]), int)
            elif key == "POINT_DATA":
                section, count = "point", int(w[1])
            elif key == "CELL_DATA":
                section, count = "cell", int(w[1])
            elif key in ("SCALARS", "VECTORS"):
                name = w[1]
                if key == "VECTORS":
                    ncomp = 3
                else:
                    ncomp = int(w[3]) if len(w) > 3 else 1
                    pos = f.tell()
                    nxt = f.readline()
                    if not nxt.upper().startswith("LOOKUP_TABLE"):
                        f.seek(pos)
                if section == "point" and name == "displacement":
                    v = _take(f, ncomp * count, float)
                    ux, uy = v[0::ncomp], v[1::ncomp]
                elif section == "cell" and name == "body":
                    body = _take(f, count, lambda s: int(float(s)))
                else:
                    _take(f, ncomp * count, lambda s: None)
    if None in (xs, cells, types, ux, body):
        raise ValueError(f"{path}: missing POINTS, CELLS, displacement or body")
    return xs, ys, cells, types, ux, uy, body


def read_csv(path):
    with open(path) as f:
        head = f.readline().strip().split(",")
        rows = []
        for line in f:
            w = line.strip().split(",")
            if len(w) == len(head):
                rows.append({k: (float(v) if v else None) for k, v in zip(head, w)})
    return rows


def read_summary(path):
    d = {}
    with open(path) as f:
        for line in f:
            w = line.split()
            if len(w) >= 2:
                if w[0] == "reaction":
                    d["reaction " + w[1]] = (float(w[2]), float(w[3]))
                else:
                    d[w[0]] = w[1]
    return d


# ----------------------------------------------------------------------------- run mesh

class BodyMesh:
    """The cells of one body of a run, with a bucket grid for point location.
    Triangles carry (x0, y0, inverse Jacobian, constant gradient); quads keep
    their vertices and nodal displacements."""

    def __init__(self, xs, ys, ux, uy, cells, types, ids):
        self.tri = []       # (x0, y0, d11, d12, d21, d22, gxx, gxy, gyx, gyy)
        self.quad = []      # (vertex xs, ys, uxs, uys)
        self.items = []     # ("t", index) or ("q", index)
        boxes = []
        for c in ids:
            v = cells[c]
            if types[c] == 5:
                i, j, k = v
                x0, y0 = xs[i], ys[i]
                a11, a12 = xs[j] - x0, xs[k] - x0
                a21, a22 = ys[j] - y0, ys[k] - y0
                det = a11 * a22 - a12 * a21
                d11, d12, d21, d22 = a22 / det, -a12 / det, -a21 / det, a11 / det
                # grad u = (du/dxi, du/deta) * D
                dux1, dux2 = ux[j] - ux[i], ux[k] - ux[i]
                duy1, duy2 = uy[j] - uy[i], uy[k] - uy[i]
                g = (dux1 * d11 + dux2 * d21, dux1 * d12 + dux2 * d22,
                     duy1 * d11 + duy2 * d21, duy1 * d12 + duy2 * d22)
                self.items.append((0, len(self.tri)))
                self.tri.append((x0, y0, d11, d12, d21, d22) + g)
            elif types[c] == 9:
                self.items.append((1, len(self.quad)))
                self.quad.append(([xs[n] for n in v], [ys[n] for n in v],
                                  [ux[n] for n in v], [uy[n] for n in v]))
            else:
                raise ValueError(f"cell type {types[c]} not supported")
            px = [xs[n] for n in v]
            py = [ys[n] for n in v]
            boxes.append((min(px), max(px), min(py), max(py)))
        # Multi-level bucket grid: level L has square buckets of side s0 / 2^L
        # (s0 the largest cell size); a cell goes to the level whose buckets are
        # just larger than it, so it meets at most 2 x 2 buckets there, and a
        # graded mesh (hc << hf) keeps a few cells per bucket at every level.
        self.x0 = min(b[0] for b in boxes)
        self.y0 = min(b[2] for b in boxes)
        s0 = max(max(b[1] - b[0], b[3] - b[2]) for b in boxes) * 1.000001
        self.buckets = {}
        levels = set()
        for item, (bx0, bx1, by0, by1) in enumerate(boxes):
            size = max(bx1 - bx0, by1 - by0, 1e-300)
            lev = min(24, int(math.floor(math.log2(s0 / size))))
            inv = (1 << lev) / s0
            levels.add(lev)
            for i in range(int((bx0 - self.x0) * inv), int((bx1 - self.x0) * inv) + 1):
                for j in range(int((by0 - self.y0) * inv), int((by1 - self.y0) * inv) + 1):
                    self.buckets.setdefault((lev << 50) | (i << 25) | j, []).append(item)
        self.levels = [(lev << 50, (1 << lev) / s0) for lev in sorted(levels)]
        self.last = 0

    def _local(self, item, x, y):
        """Local coordinates and the 'outside' measure (<= 0 inside) of a point."""
        kind, k = self.items[item]
        if kind == 0:
            t = self.tri[k]
            dx, dy = x - t[0], y - t[1]
            xi = t[2] * dx + t[3] * dy
            eta = t[4] * dx + t[5] * dy
            return xi, eta, -min(xi, eta, 1.0 - xi - eta)
        px, py = self.quad[k][0], self.quad[k][1]
        xi = eta = 0.0
        for _ in range(20):            # Newton on the bilinear map, (xi, eta) in [-1, 1]^2
            n = ((1 - xi) * (1 - eta) / 4, (1 + xi) * (1 - eta) / 4,
                 (1 + xi) * (1 + eta) / 4, (1 - xi) * (1 + eta) / 4)
            dxi = (-(1 - eta) / 4, (1 - eta) / 4, (1 + eta) / 4, -(1 + eta) / 4)
            deta = (-(1 - xi) / 4, -(1 + xi) / 4, (1 + xi) / 4, (1 - xi) / 4)
            rx = sum(a * b for a, b in zip(n, px)) - x
            ry = sum(a * b for a, b in zip(n, py)) - y
            j11 = sum(a * b for a, b in zip(dxi, px)); j12 = sum(a * b for a, b in zip(deta, px))
            j21 = sum(a * b for a, b in zip(dxi, py)); j22 = sum(a * b for a, b in zip(deta, py))
            det = j11 * j22 - j12 * j21
            sxi = (j22 * rx - j12 * ry) / det
            seta = (-j21 * rx + j11 * ry) / det
            xi -= sxi; eta -= seta
            if abs(sxi) + abs(seta) < 1e-13:
                break
        return xi, eta, max(abs(xi), abs(eta)) - 1.0

    def locate(self, x, y):
        """Item of the cell holding (x, y), or of the nearest cell (extension)."""
        if self._local(self.last, x, y)[2] <= 1e-8:
            return self.last
        best, bestout = -1, 1e300
        for key, inv in self.levels:
            i, j = int((x - self.x0) * inv), int((y - self.y0) * inv)
            for item in self.buckets.get(key | (i << 25) | j, ()) if i >= 0 and j >= 0 else ():
                out = self._local(item, x, y)[2]
                if out <= 1e-8:
                    self.last = item
                    return item
                if out < bestout:
                    best, bestout = item, out
        # inside no cell (outside a chord-meshed curved boundary): the nearest
        # cell among the 3 x 3 buckets around the point at every level, or
        # among all cells if those are empty
        for key, inv in self.levels:
            i, j = int((x - self.x0) * inv), int((y - self.y0) * inv)
            for ii in (i - 1, i, i + 1):
                for jj in (j - 1, j, j + 1):
                    if ii >= 0 and jj >= 0:
                        for item in self.buckets.get(key | (ii << 25) | jj, ()):
                            out = self._local(item, x, y)[2]
                            if out < bestout:
                                best, bestout = item, out
        if best < 0:
            for item in range(len(self.items)):
                out = self._local(item, x, y)[2]
                if out < bestout:
                    best, bestout = item, out
        return best

    def gradient(self, item, x, y):
        kind, k = self.items[item]
        if kind == 0:
            return self.tri[k][6:10]
        xi, eta, _ = self._local(item, x, y)
        return quad_gradient(self.quad[k], xi, eta)


def quad_gradient(q, xi, eta):
    """(dux/dx, dux/dy, duy/dx, duy/dy) of a Q1 cell at local (xi, eta), and
    the Jacobian determinant as fifth value."""
    px, py, qx, qy = q
    dxi = (-(1 - eta) / 4, (1 - eta) / 4, (1 + eta) / 4, -(1 + eta) / 4)
    deta = (-(1 - xi) / 4, -(1 + xi) / 4, (1 + xi) / 4, (1 - xi) / 4)
    j11 = sum(a * b for a, b in zip(dxi, px)); j12 = sum(a * b for a, b in zip(deta, px))
    j21 = sum(a * b for a, b in zip(dxi, py)); j22 = sum(a * b for a, b in zip(deta, py))
    det = j11 * j22 - j12 * j21
    # d/dx = ( j22 d/dxi - j21 d/deta) / det ; d/dy = (-j12 d/dxi + j11 d/deta) / det
    uxi = sum(a * b for a, b in zip(dxi, qx)); ueta = sum(a * b for a, b in zip(deta, qx))
    vxi = sum(a * b for a, b in zip(dxi, qy)); veta = sum(a * b for a, b in zip(deta, qy))
    return ((j22 * uxi - j21 * ueta) / det, (-j12 * uxi + j11 * ueta) / det,
            (j22 * vxi - j21 * veta) / det, (-j12 * vxi + j11 * veta) / det, det)


def split_mesh(vtk):
    xs, ys, cells, types, ux, uy, body = vtk
    nb = max(body)
    ids = [[] for _ in range(nb)]
    for c, b in enumerate(body):
        ids[b - 1].append(c)
    return ids


# ----------------------------------------------------------------------------- H1 error

def lame(e_mod, nu, plane):
    mu = e_mod / (2 * (1 + nu))
    lam = e_mod * nu / ((1 + nu) * (1 - 2 * nu))
    if plane == "stress":
        lam = 2 * lam * mu / (lam + 2 * mu)
    return lam, mu


def energy_density(g, lam, mu):
    exx, eyy, gxy = g[0], g[3], g[1] + g[2]
    return lam * (exx + eyy) ** 2 + 2 * mu * (exx * exx + eyy * eyy) + mu * gxy * gxy


def _sub_points():
    """Centroids of the 16 congruent pieces of the reference triangle (4 x 4 split)."""
    pts = []
    n = 4
    for i in range(n):
        for j in range(n - i):
            pts.append(((3 * i + 1) / (3 * n), (3 * j + 1) / (3 * n)))          # upward
            if i + j < n - 1:
                pts.append(((3 * i + 2) / (3 * n), (3 * j + 2) / (3 * n)))      # downward
    return pts


SUBPTS = _sub_points()
GAUSS2 = (-1 / math.sqrt(3), 1 / math.sqrt(3))


def reference_cells(vtk, window):
    """Per body: list of ('t', area, centroid, vertices, gradient) or ('q', cell)."""
    xs, ys, cells, types, ux, uy, body = vtk
    nb = max(body)
    out = [[] for _ in range(nb)]
    for c, v in enumerate(cells):
        px = [xs[n] for n in v]
        py = [ys[n] for n in v]
        cx, cy = sum(px) / len(v), sum(py) / len(v)
        if window and not (window[0] <= cx <= window[1] and window[2] <= cy <= window[3]):
            continue
        if types[c] == 5:
            i, j, k = v
            a11, a12, a21, a22 = px[1] - px[0], px[2] - px[0], py[1] - py[0], py[2] - py[0]
            det = a11 * a22 - a12 * a21
            d11, d12, d21, d22 = a22 / det, -a12 / det, -a21 / det, a11 / det
            dux1, dux2 = ux[j] - ux[i], ux[k] - ux[i]
            duy1, duy2 = uy[j] - uy[i], uy[k] - uy[i]
            g = (dux1 * d11 + dux2 * d21, dux1 * d12 + dux2 * d22,
                 duy1 * d11 + duy2 * d21, duy1 * d12 + duy2 * d22)
            out[body[c] - 1].append((0, abs(det) / 2, cx, cy, px, py, a11, a12, a21, a22, g))
        elif types[c] == 9:
            out[body[c] - 1].append((1, (px, py, [ux[n] for n in v], [uy[n] for n in v])))
    return out


def h1_error(refcells, run, mats):
    """Squared broken H1 seminorm, energy of the error and of the reference, per body;
    and the share of reference triangles integrated exactly (nested in a run triangle)."""
    ids = split_mesh(run)
    xs, ys, cells, types, ux, uy, body = run
    res = []
    nexact = ntri = 0
    for b, rc in enumerate(refcells):
        lam, mu = mats[min(b, len(mats) - 1)]
        m = BodyMesh(xs, ys, ux, uy, cells, types, ids[b])
        if not m.quad:
            r, ne, nt = h1_body_triangles(rc, m, lam, mu)
        else:
            r, ne, nt = h1_body_general(rc, m, lam, mu)
        res.append(r)
        nexact += ne
        ntri += nt
    return res, (nexact / ntri if ntri else 0.0)


def h1_body_triangles(rc, m, lam, mu):
    """h1_error on one body whose run mesh has triangles only (the fast path)."""
    tri, buckets, levels = m.tri, m.buckets, m.levels
    bx0, by0 = m.x0, m.y0
    tol, vtol = 1e-8, 1e-6     # vertices carry the VTK file's 10 significant digits
    e1 = en = r1 = rn = 0.0
    nexact = ntri = 0
    last = tri[0]
    for c in rc:
        if c[0] != 0:
            r, ne, nt = h1_body_general([c], m, lam, mu)
            e1 += r[0]; en += r[1]; r1 += r[2]; rn += r[3]
            continue
        _, area, cx, cy, px, py, a11, a12, a21, a22, g = c
        ntri += 1
        r1 += area * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3])
        rn += area * energy_density(g, lam, mu)
        # the run triangle of the previous reference triangle first, then the buckets
        t = last
        dx, dy = cx - t[0], cy - t[1]
        xi = t[2] * dx + t[3] * dy
        eta = t[4] * dx + t[5] * dy
        if not (xi >= -tol and eta >= -tol and xi + eta <= 1 + tol):
            t = None
            for key, inv in levels:
                i, j = int((cx - bx0) * inv), int((cy - by0) * inv)
                if i < 0 or j < 0:
                    continue
                for item in buckets.get(key | (i << 25) | j, ()):
                    u = tri[item]
                    dx, dy = cx - u[0], cy - u[1]
                    xi = u[2] * dx + u[3] * dy
                    eta = u[4] * dx + u[5] * dy
                    if xi >= -tol and eta >= -tol and xi + eta <= 1 + tol:
                        t = u
                        break
                if t is not None:
                    last = t
                    break
        exact = t is not None
        if exact:
            for q in range(3):
                dx, dy = px[q] - t[0], py[q] - t[1]
                xi = t[2] * dx + t[3] * dy
                eta = t[4] * dx + t[5] * dy
                if xi < -vtol or eta < -vtol or xi + eta > 1 + vtol:
                    exact = False
                    break
        if exact:
            nexact += 1
            d0, d1, d2, d3 = g[0] - t[6], g[1] - t[7], g[2] - t[8], g[3] - t[9]
            e1 += area * (d0 * d0 + d1 * d1 + d2 * d2 + d3 * d3)
            tr = d0 + d3
            gxy = d1 + d2
            en += area * (lam * tr * tr + 2 * mu * (d0 * d0 + d3 * d3) + mu * gxy * gxy)
        else:
            # a cut reference triangle: exact integration over its intersections
            # with the run triangles (Sutherland-Hodgman clipping)
            for w, h in clip_pieces(m, px, py, area, cx, cy):
                d0, d1, d2, d3 = g[0] - h[6], g[1] - h[7], g[2] - h[8], g[3] - h[9]
                e1 += w * (d0 * d0 + d1 * d1 + d2 * d2 + d3 * d3)
                tr = d0 + d3
                gxy = d1 + d2
                en += w * (lam * tr * tr + 2 * mu * (d0 * d0 + d3 * d3) + mu * gxy * gxy)
    return (e1, en, r1, rn), nexact, ntri


def clip_area(t, px, py):
    """Area of the triangle (px, py) intersected with the run triangle t (clipping
    by the half-planes lambda_k >= 0 of t's barycentric coordinates)."""
    poly = list(zip(px, py))
    x0, y0, d11, d12, d21, d22 = t[0], t[1], t[2], t[3], t[4], t[5]
    for k in range(3):
        lam = []
        for x, y in poly:
            dx, dy = x - x0, y - y0
            xi = d11 * dx + d12 * dy
            eta = d21 * dx + d22 * dy
            lam.append(xi if k == 0 else (eta if k == 1 else 1.0 - xi - eta))
        out = []
        n = len(poly)
        for i in range(n):
            a, b = lam[i], lam[(i + 1) % n]
            if a >= 0:
                out.append(poly[i])
            if (a >= 0) != (b >= 0):
                s = a / (a - b)
                p, q = poly[i], poly[(i + 1) % n]
                out.append((p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])))
        poly = out
        if len(poly) < 3:
            return 0.0
    area = 0.0
    for i in range(len(poly)):
        x1, y1 = poly[i]
        x2, y2 = poly[(i + 1) % len(poly)]
        area += x1 * y2 - x2 * y1
    return abs(area) / 2


def clip_pieces(m, px, py, area, cx, cy):
    """(weight, run triangle) pieces covering a reference triangle: its areas of
    intersection with the run triangles met (first those holding its vertices
    and centroid, then every triangle of the buckets its box meets); the area
    left over (outside the run's body) goes to the nearest run triangle."""
    tri = m.tri
    seen = set()
    pieces = []
    covered = 0.0
    first = [m.locate(px[0], py[0]), m.locate(px[1], py[1]), m.locate(px[2], py[2]), m.locate(cx, cy)]
    for item in first:
        if item in seen:
            continue
        seen.add(item)
        a = clip_area(tri[item], px, py)
        if a > 0:
            pieces.append((a, tri[item]))
            covered += a
    if covered < area * (1 - 1e-9):
        xlo, xhi, ylo, yhi = min(px), max(px), min(py), max(py)
        for key, inv in m.levels:
            for i in range(int((xlo - m.x0) * inv), int((xhi - m.x0) * inv) + 1):
                for j in range(int((ylo - m.y0) * inv), int((yhi - m.y0) * inv) + 1):
                    if i < 0 or j < 0:
                        continue
                    for item in m.buckets.get(key | (i << 25) | j, ()):
                        if item in seen:
                            continue
                        seen.add(item)
                        a = clip_area(tri[item], px, py)
                        if a > 0:
                            pieces.append((a, tri[item]))
                            covered += a
        if covered < area * (1 - 1e-9):
            pieces.append((area - covered, tri[first[3]]))
    return pieces


def h1_body_general(rc, m, lam, mu):
    """h1_error on one body, any mix of P1 triangles and Q1 quads (run and reference)."""
    e1 = en = r1 = rn = 0.0
    nexact = ntri = 0
    for c in rc:
        if c[0] == 0:
            _, area, cx, cy, px, py, a11, a12, a21, a22, g = c
            ntri += 1
            r1 += area * (g[0] ** 2 + g[1] ** 2 + g[2] ** 2 + g[3] ** 2)
            rn += area * energy_density(g, lam, mu)
            item = m.locate(cx, cy)
            exact = False
            if m.items[item][0] == 0:
                exact = all(m._local(item, px[q], py[q])[2] <= 1e-6 for q in range(3))
            if exact:
                nexact += 1
                pts = ((1.0 / 3.0, 1.0 / 3.0, area),)
            else:
                pts = [(s, t, area / len(SUBPTS)) for s, t in SUBPTS]
            for s, t, w in pts:
                x = px[0] + a11 * s + a12 * t
                y = py[0] + a21 * s + a22 * t
                h = m.gradient(m.locate(x, y), x, y)
                d = (g[0] - h[0], g[1] - h[1], g[2] - h[2], g[3] - h[3])
                e1 += w * (d[0] ** 2 + d[1] ** 2 + d[2] ** 2 + d[3] ** 2)
                en += w * energy_density(d, lam, mu)
        else:
            q = c[1]
            for xi in GAUSS2:
                for eta in GAUSS2:
                    gq = quad_gradient(q, xi, eta)
                    w = gq[4]
                    nn = ((1 - xi) * (1 - eta) / 4, (1 + xi) * (1 - eta) / 4,
                          (1 + xi) * (1 + eta) / 4, (1 - xi) * (1 + eta) / 4)
                    x = sum(a * p for a, p in zip(nn, q[0]))
                    y = sum(a * p for a, p in zip(nn, q[1]))
                    h = m.gradient(m.locate(x, y), x, y)
                    d = (gq[0] - h[0], gq[1] - h[1], gq[2] - h[2], gq[3] - h[3])
                    r1 += w * (gq[0] ** 2 + gq[1] ** 2 + gq[2] ** 2 + gq[3] ** 2)
                    rn += w * energy_density(gq, lam, mu)
                    e1 += w * (d[0] ** 2 + d[1] ** 2 + d[2] ** 2 + d[3] ** 2)
                    en += w * energy_density(d, lam, mu)
    return (e1, en, r1, rn), nexact, ntri


# ----------------------------------------------------------------------------- pressure

def profile(path, pair, axis):
    rows = [r for r in read_csv(path) if int(r["pair"]) == pair]
    rows.sort(key=lambda r: r["s"])
    return [r[axis] for r in rows], [r["pressure"] for r in rows]


def interp(xs, ps, x):
    """Piecewise linear interpolation (constant beyond the ends); xs increasing."""
    lo, hi = 0, len(xs) - 1
    if x <= xs[0]:
        return ps[0]
    if x >= xs[-1]:
        return ps[-1]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    t = (x - xs[lo]) / (xs[hi] - xs[lo])
    return (1 - t) * ps[lo] + t * ps[hi]


def l2_diff(xa, pa, xb, pb, a, b):
    """int_a^b (p_a - p_b)^2 and int_a^b p_b^2, exact for piecewise linear data."""
    pts = sorted(set([a, b] + [x for x in xa + xb if a < x < b]))
    num = den = 0.0
    for x0, x1 in zip(pts[:-1], pts[1:]):
        h = x1 - x0
        if h <= 0:
            continue
        d0 = interp(xa, pa, x0) - interp(xb, pb, x0)
        d1 = interp(xa, pa, x1) - interp(xb, pb, x1)
        r0, r1 = interp(xb, pb, x0), interp(xb, pb, x1)
        num += h * (d0 * d0 + d0 * d1 + d1 * d1) / 3
        den += h * (r0 * r0 + r0 * r1 + r1 * r1) / 3
    return num, den


def resultant(xs, ps):
    """F(x_i) = int_{x_i}^{end} p ds by the trapezoid rule (exact for linear p)."""
    f = [0.0] * len(xs)
    for i in range(len(xs) - 2, -1, -1):
        f[i] = f[i + 1] + 0.5 * (ps[i] + ps[i + 1]) * (xs[i + 1] - xs[i])
    return f


# ----------------------------------------------------------------------------- main

def options(argv, spec):
    """Split argv into positional words and the options named in spec (name -> repeat)."""
    pos, opt = [], {k: [] for k in spec}
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in spec:
            opt[a].append(argv[i + 1])
            i += 2
        elif a.startswith("-") and len(a) > 1 and not a[1].isdigit():
            sys.exit(f"c2derr.py: unknown option {a}")
        else:
            pos.append(a)
            i += 1
    return pos, opt


def main_h1(argv):
    pos, opt = options(argv, ("-m", "--plane", "--window"))
    if len(pos) < 2:
        sys.exit("usage: c2derr.py h1 REF.vtk RUN.vtk [...] [-m E,nu ...] [--plane strain|stress] "
                 "[--window x0,x1,y0,y1]")
    plane = opt["--plane"][-1] if opt["--plane"] else "strain"
    mats = [lame(*map(float, m.split(",")), plane) for m in opt["-m"]] or [lame(1.0, 0.0, plane)]
    window = tuple(map(float, opt["--window"][-1].split(","))) if opt["--window"] else None
    ref = reference_cells(read_vtk(pos[0]), window)
    for path in pos[1:]:
        res, nested = h1_error(ref, read_vtk(path), mats)
        e1 = sum(r[0] for r in res); en = sum(r[1] for r in res)
        r1 = sum(r[2] for r in res); rn = sum(r[3] for r in res)
        line = [path, f"{math.sqrt(e1):.6e}", f"{math.sqrt(e1 / r1):.6e}",
                f"{math.sqrt(en):.6e}", f"{math.sqrt(en / rn):.6e}", f"{nested:.4f}"]
        line += [f"{math.sqrt(r[0]):.6e}" for r in res]
        print(",".join(line))
        sys.stdout.flush()


def main_pressure(argv):
    pos, opt = options(argv, ("--pair", "--xmin", "--xmax", "--axis"))
    if len(pos) < 2:
        sys.exit("usage: c2derr.py pressure REF_contact.csv RUN_contact.csv [...] [--pair N] "
                 "[--xmin A] [--xmax B] [--axis x|y]")
    pair = int(opt["--pair"][-1]) if opt["--pair"] else 1
    axis = opt["--axis"][-1] if opt["--axis"] else "x"
    rx, rp = profile(pos[0], pair, axis)
    if rx[0] > rx[-1]:
        rx, rp = rx[::-1], rp[::-1]
    a = float(opt["--xmin"][-1]) if opt["--xmin"] else rx[0]
    b = float(opt["--xmax"][-1]) if opt["--xmax"] else rx[-1]
    rF = resultant(rx, rp)
    for path in pos[1:]:
        xs, ps = profile(path, pair, axis)
        if xs[0] > xs[-1]:
            xs, ps = xs[::-1], ps[::-1]
        num, den = l2_diff(xs, ps, rx, rp, a, b)
        F = resultant(xs, ps)
        fn, _ = l2_diff(xs, F, rx, rF, rx[0], rx[-1])
        fmax = max(max(abs(f - interp(rx, rF, x)) for f, x in zip(F, xs)),
                   max(abs(f - interp(xs, F, x)) for f, x in zip(rF, rx)))
        length = rx[-1] - rx[0]
        print(f"{path},{math.sqrt(num / den):.6e},{math.sqrt(fn / length) / rF[0]:.6e},{fmax / rF[0]:.6e}")


def main_hertz(argv):
    pos, opt = options(argv, ("--E", "--nu", "--R", "--load"))
    if len(pos) < 2 or len(pos) % 2:
        sys.exit("usage: c2derr.py hertz RUN_contact.csv RUN.summary [...] --E E --nu nu --R R [--load B:b]")
    e_mod = float(opt["--E"][-1]); nu = float(opt["--nu"][-1]); radius = float(opt["--R"][-1])
    load = opt["--load"][-1] if opt["--load"] else "disk:top"
    estar = 1.0 / (2 * (1 - nu * nu) / e_mod)
    gx, gw = gauss_legendre8()
    for csv, summ in zip(pos[0::2], pos[1::2]):
        s = read_summary(summ)
        P = abs(s["reaction " + load][1])
        a = math.sqrt(4 * P * radius / (math.pi * estar))
        p0 = 2 * P / (math.pi * a)
        xs, ps = profile(csv, 1, "x")
        if xs[0] > xs[-1]:
            xs, ps = xs[::-1], ps[::-1]
        trap = lambda f: sum(0.5 * (f[i] + f[i + 1]) * (xs[i + 1] - xs[i]) for i in range(len(xs) - 1))
        force = trap(ps)
        # second moment of the piecewise linear p: exact per piece
        m2 = 0.0
        for i in range(len(xs) - 1):
            x0, x1, q0, q1 = xs[i], xs[i + 1], ps[i], ps[i + 1]
            for t, w in zip(gx, gw):
                x = x0 + (x1 - x0) * t
                m2 += w * (x1 - x0) * (q0 + (q1 - q0) * t) * x * x
        ah = 2 * math.sqrt(m2 / force)
        p0h = max(ps)
        exact = lambda x: p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2))
        pts = sorted(set([-a, a] + [x for x in xs if -a < x < a]))
        num = den = 0.0
        for x0, x1 in zip(pts[:-1], pts[1:]):
            for t, w in zip(gx, gw):
                # substitute x = a sin(theta) would be exact; 8 Gauss points per piece suffice
                x = x0 + (x1 - x0) * t
                d = interp(xs, ps, x) - exact(x)
                num += w * (x1 - x0) * d * d
                den += w * (x1 - x0) * exact(x) ** 2
        print(f"{csv},{P:.6e},{a:.6e},{p0:.6e},{ah:.6e},{p0h:.6e},{abs(ah - a) / a:.6e},"
              f"{abs(p0h - p0) / p0:.6e},{math.sqrt(num / den):.6e}")


def gauss_legendre8():
    """8-point Gauss-Legendre rule on [0, 1]."""
    x = [0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363]
    w = [0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763]
    pts, wts = [], []
    for xi, wi in zip(x, w):
        for s in (-1, 1):
            pts.append(0.5 + 0.5 * s * xi)
            wts.append(0.5 * wi)
    return pts, wts


if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1] not in ("h1", "pressure", "hertz"):
        sys.exit(__doc__)
    {"h1": main_h1, "pressure": main_pressure, "hertz": main_hertz}[sys.argv[1]](sys.argv[2:])
