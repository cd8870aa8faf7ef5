"""The true error of a contact pressure profile against a reference: both
read from contact tables (the rows of the effective zone), both piecewise
linear between their slave nodes, and the relative L2 difference integrated
exactly over the union of their breakpoints.  Used by tests/estimate and by
bench/adapt.sh (as a program: pressure_error.py REFERENCE.csv TABLE.csv ...
prints the error of each table, in per cent)."""
import sys
from c2dcheck import contact_table


def profile(rows):
    """(x, pressure) of the rows inside the effective zone (status 0 or 1), by x."""
    return sorted((r["x"], r["pressure"] or 0.0) for r in rows if r["status"] is not None and r["status"] >= 0)


def at(prof, x):
    """The piecewise linear profile at x (0 outside)."""
    if x < prof[0][0] or x > prof[-1][0]:
        return 0.0
    lo, hi = 0, len(prof) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if prof[mid][0] <= x:
            lo = mid
        else:
            hi = mid
    (x0, p0), (x1, p1) = prof[lo], prof[hi]
    return p0 if x1 == x0 else p0 + (p1 - p0) * (x - x0) / (x1 - x0)


def l2_difference(a, b):
    """||a - b|| / ||b|| over the union of their breakpoints: exact for piecewise linear a, b."""
    xs = sorted(set(x for x, _ in a) | set(x for x, _ in b))
    num = den = 0.0
    for x0, x1 in zip(xs, xs[1:]):
        d0, d1 = at(a, x0) - at(b, x0), at(a, x1) - at(b, x1)
        r0, r1 = at(b, x0), at(b, x1)
        num += (x1 - x0) * (d0 * d0 + d0 * d1 + d1 * d1) / 3
        den += (x1 - x0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3
    return (num / den) ** 0.5


def table_error(table, reference):
    """The relative L2 error of the pressure of contact table `table` against `reference`."""
    return l2_difference(profile(contact_table(table)), profile(contact_table(reference)))


if __name__ == "__main__":
    for path in sys.argv[2:]:
        print(f"{100 * table_error(path, sys.argv[1]):.4f}")
