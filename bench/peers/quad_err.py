#!/usr/bin/python3
"""Second error measure for a finished bench/peers.sh run: the L2 norm of the
pressure error along the whole contact line,

    err_q = || p_h - p_H ||_L2 / || p_H ||_L2,     || p_H ||^2 = 4 a p0^2 / 3,

p_h the piecewise-linear interpolant of each code's nodal pressures (x
sorted), p_H the Hertz pressure from the code's own load P (zero for |x| > a),
integrated by 5-point Gauss on every segment split at x = +-a.  Unlike the
node-sampled error of hertz_err.py it does not depend on where x = a falls
between nodes, so it decreases monotonically along the sweep.

    quad_err.py [OUT]    OUT: bench/out/peers (runs.csv and the profiles)
prints code, hc, dofs, node-sampled error, err_q and the median CPU time.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hertz_err import read_profile, hertz  # noqa: E402

GAUSS5 = [(-0.9061798459386640, 0.2369268850561891), (-0.5384693101056831, 0.4786286704993665),
          (0.0, 0.5688888888888889), (0.5384693101056831, 0.4786286704993665),
          (0.9061798459386640, 0.2369268850561891)]
FOLDER = {"contact2d": "contact2d", "getfem": "getfem", "calculix": "ccx"}


def quad_err(xs, ps, P):
    a, p0 = hertz(P)
    pts = sorted(zip(xs, ps))
    num = 0.0
    for (x0, q0), (x1, q1) in zip(pts, pts[1:]):
        cuts = [x0] + [c for c in (-a, a) if x0 < c < x1] + [x1]
        for u0, u1 in zip(cuts, cuts[1:]):
            h = u1 - u0
            for t, w in GAUSS5:
                x = 0.5 * (u0 + u1) + 0.5 * h * t
                ph = q0 + (q1 - q0) * (x - x0) / (x1 - x0)
                exact = p0 * math.sqrt(max(0.0, 1.0 - x * x / (a * a)))
                num += 0.5 * h * w * (ph - exact) ** 2
    return math.sqrt(num / (4.0 * a * p0 * p0 / 3.0))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "out", "peers")
    print(f"{'code':10s} {'hc':>7s} {'dofs':>7s} {'node err%':>10s} {'err_q%':>8s} {'cpu s':>8s}")
    for r in csv.DictReader(open(os.path.join(out, "runs.csv"))):
        prof = os.path.join(out, FOLDER.get(r["code"], r["code"]), "hc" + r["hc"], "profile.txt")
        try:
            meta, xs, ps = read_profile(prof)
            e = quad_err(xs, ps, float(meta["P"]))
        except (OSError, KeyError, ValueError, ZeroDivisionError):
            e = float("nan")
        cpu = sorted(float(t) for t in r["cpu_s"].split()) if r["cpu_s"] else []
        med = cpu[len(cpu) // 2] if cpu else float("nan")
        print(f"{r['code']:10s} {r['hc']:>7s} {int(r['dofs']):7d} {float(r['err']) * 100:10.3f} {e * 100:8.3f} {med:8.3f}")


if __name__ == "__main__":
    main()
