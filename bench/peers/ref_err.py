#!/usr/bin/python3
"""Pressure error of a Hertz H solution against a reference solution of the
same finite problem, by quadrature along the contact line.

A profile (hertz_err.py's format: '# key value' lines, then 'x p' rows) holds
the pressure at the nodes of the slave line (the block top) sorted by x; its
'# order' line (1 when absent) says how the pressure runs between the nodes:

  order 1: piecewise linear between consecutive nodes;
  order 2: piecewise quadratic on the node triples (x_2k, x_2k+1, x_2k+2)
           (corner, midside, corner of a quadratic edge; an odd count of nodes).

Outside the profile's span the pressure is 0 (no contact there).  With p_h the
run's pressure and p_r the reference's, both extended by 0,

    err_L2 = || p_h - p_r ||_L2 / || p_r ||_L2,

integrated by 5-point Gauss-Legendre on every interval between two
consecutive break points of either profile: the integrand is there a
polynomial of degree at most 4, so the quadrature is exact to round-off, and
nowhere is a node sampled (the error does not depend on where the zone's end
falls between two nodes, unlike hertz_err.py's node-sampled error).

    ref_err.py REF.prof RUN.prof...   prints 'file dofs err_L2' per run
    ref_err.py --self-test            closed-form checks (PASS/FAIL lines)
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hertz_err import read_profile  # noqa: E402

GAUSS5 = [(-0.9061798459386640, 0.2369268850561891), (-0.5384693101056831, 0.4786286704993665),
          (0.0, 0.5688888888888889), (0.5384693101056831, 0.4786286704993665),
          (0.9061798459386640, 0.2369268850561891)]


class Profile:
    """A piecewise-polynomial pressure along x, zero outside its nodes' span."""

    def __init__(self, xs, ps, order=1):
        pts = sorted(zip(xs, ps))
        self.x = [x for x, _ in pts]
        self.p = [p for _, p in pts]
        self.order = order
        if order not in (1, 2):
            raise ValueError(f"order {order}: 1 or 2 expected")
        if len(self.x) < order + 1 or (order == 2 and len(self.x) % 2 == 0):
            raise ValueError(f"{len(self.x)} nodes for order {order} (order 2 takes an odd count, at least 3)")
        # the pieces: (x0, x1, node indices of the piece)
        step = order
        self.pieces = [(self.x[k], self.x[k + step], list(range(k, k + step + 1)))
                       for k in range(0, len(self.x) - step, step)]

    def breaks(self):
        return [pc[0] for pc in self.pieces] + [self.pieces[-1][1]]

    def value(self, x, piece):
        """Lagrange interpolation on the nodes of one piece."""
        idx = self.pieces[piece][2]
        v = 0.0
        for i in idx:
            li = 1.0
            for j in idx:
                if j != i:
                    li *= (x - self.x[j]) / (self.x[i] - self.x[j])
            v += li * self.p[i]
        return v


def _piece_at(prof, x):
    """Index of the piece of prof containing x (None outside the span); binary search."""
    if x < prof.pieces[0][0] or x > prof.pieces[-1][1]:
        return None
    lo, hi = 0, len(prof.pieces) - 1
    while lo < hi:
        mid = (lo + hi) // 2
        if x > prof.pieces[mid][1]:
            lo = mid + 1
        else:
            hi = mid
    return lo


def l2_diff(run, ref):
    """(|| p_run - p_ref ||_L2, || p_ref ||_L2) by 5-point Gauss on the merged break points."""
    cuts = sorted(set(run.breaks()) | set(ref.breaks()))
    num = den = 0.0
    for u0, u1 in zip(cuts, cuts[1:]):
        h = u1 - u0
        if h <= 0.0:
            continue
        xm = 0.5 * (u0 + u1)
        kr, kf = _piece_at(run, xm), _piece_at(ref, xm)   # the midpoint picks the piece of each
        for t, w in GAUSS5:
            x = xm + 0.5 * h * t
            ph = run.value(x, kr) if kr is not None else 0.0
            pr = ref.value(x, kf) if kf is not None else 0.0
            num += 0.5 * h * w * (ph - pr) ** 2
            den += 0.5 * h * w * pr * pr
    return math.sqrt(num), math.sqrt(den)


def load(path):
    """(meta, Profile) of a profile file."""
    meta, xs, ps = read_profile(path)
    return meta, Profile(xs, ps, int(meta.get("order", 1)))


def rel_error(run_path, ref_path):
    """(dofs, relative L2 pressure error) of a run profile against a reference profile."""
    meta, run = load(run_path)
    _, ref = load(ref_path)
    num, den = l2_diff(run, ref)
    return int(meta.get("dofs", 0)), num / den


class Checks:
    """PASS/FAIL lines of a self-test, and the count of failures."""

    def __init__(self):
        self.fails = 0

    def __call__(self, ok, name, detail):
        print(("PASS " if ok else "FAIL ") + name + ("" if ok else ": " + detail))
        self.fails += 0 if ok else 1


def self_test():
    """Closed-form checks; returns the number of failures."""
    check = Checks()

    # 1. linear reference x + 2 on [-1, 1] (5 nodes), run = the same line + c on
    #    7 other nodes: || c ||^2 = 2 c^2, || x + 2 ||^2 = 2/3 + 8.
    c = 0.01
    ref = Profile([-1 + 0.5 * k for k in range(5)], [-1 + 0.5 * k + 2 for k in range(5)])
    xs = [-1.0, -0.7, -0.3, 0.1, 0.2, 0.75, 1.0]
    run = Profile(xs, [x + 2 + c for x in xs])
    num, den = l2_diff(run, ref)
    want = math.sqrt(2 * c * c / (2.0 / 3.0 + 8.0))
    check(abs(num / den - want) <= 1e-13 * want, "ref_err: shifted line on non-matching nodes",
          f"{num / den!r} != {want!r}")
    # 2. reference x^2 on [0, 1] exactly (order 2, 3 nodes); run = its P1
    #    interpolant on n uniform segments: the error on each is t (h - t),
    #    whose square integrates to h^5 / 30; || x^2 ||^2 = 1/5.
    ref = Profile([0.0, 0.5, 1.0], [0.0, 0.25, 1.0], order=2)
    for n in (1, 3, 10):
        xs = [k / n for k in range(n + 1)]
        num, den = l2_diff(Profile(xs, [x * x for x in xs]), ref)
        want = math.sqrt(n * (1.0 / n) ** 5 / 30.0 / 0.2)
        check(abs(num / den - want) <= 1e-12 * want, f"ref_err: P1 interpolant of x^2, n = {n}",
              f"{num / den!r} != {want!r}")
    # 3. a quadratic run x^2 on [-1, 1] (other nodes) against the reference
    #    x^2 on [0, 1]: zero difference on [0, 1], and the run's part on
    #    [-1, 0] counts in full (|| x^2 ||^2 = 1/5 there); a run shorter than
    #    the reference: the missing part counts in full too (reference 1 on
    #    [-1, 1], run 1 on [-0.5, 0.5]: error^2 = 1 / 2).
    xs = [-1.0 + 0.25 * k for k in range(9)]
    run = Profile(xs, [x * x for x in xs], order=2)
    num, _ = l2_diff(run, ref)
    check(abs(num - math.sqrt(0.2)) <= 1e-14, "ref_err: quadratic run against a quadratic reference of half its span",
          f"error {num!r} != sqrt(1/5)")
    num, den = l2_diff(Profile([-0.5, 0.5], [1.0, 1.0]), Profile([-1.0, 0.0, 1.0], [1.0, 1.0, 1.0]))
    check(abs(num / den - math.sqrt(0.5)) <= 1e-14, "ref_err: no pressure outside the run's span",
          f"{num / den!r}")
    return check.fails


def main(argv):
    if argv[1:2] == ["--self-test"]:
        return 1 if self_test() else 0
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    for fn in argv[2:]:
        d, e = rel_error(fn, argv[1])
        print(f"{fn} {d} {e:.6e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
