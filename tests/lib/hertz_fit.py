"""The centre and half-width of a Hertz-like contact zone from a contact table.

fit_zone(rows) fits p^2 = c0 + c1 x + c2 x^2 (Hertz's p = p0 sqrt(1 - (x - xc)^2 / a^2)
squared) by least squares over the nodes of the inner 80 % of the zone, so that
the profile, not one node at the zone's ends, sets xc and a.  rows: the contact
table's rows (dicts with "x" and "pressure")."""
import math


def _solve3(m, v):
    """Cramer's rule for a 3 x 3 system."""
    def det(x):
        return (x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) - x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0])
                + x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]))
    d0 = det(m)
    out = []
    for j in range(3):
        mj = [row[:] for row in m]
        for i in range(3):
            mj[i][j] = v[i]
        out.append(det(mj) / d0)
    return out


def fit_zone(rows):
    """(xc, a): the fitted centre and half-width of the zone."""
    act = [r["x"] for r in rows if r["pressure"] > 0]
    mid, half = 0.5 * (min(act) + max(act)), 0.5 * (max(act) - min(act))
    pts = [(r["x"] - mid, r["pressure"]**2) for r in rows if abs(r["x"] - mid) < 0.8 * half]
    m = [[sum(x**(i + j) for x, _ in pts) for j in range(3)] for i in range(3)]
    v = [sum(p * x**i for x, p in pts) for i in range(3)]
    c0, c1, c2 = _solve3(m, v)
    xc = -c1 / (2 * c2)
    return mid + xc, math.sqrt(xc**2 - c0 / c2)
