#!/usr/bin/python3
"""Sanity checks of the O-ring reference against closed forms.

    checks.py [reference.csv]        (default: the one next to this script)

Exit 1 when a check fails.  E = 9 K mu / (3 K + mu), nu = (3 K - 2 mu) / (2 (3 K + mu))
(mu = 1, K = 1000: E = 2.999, nu = 0.4995), R = 2.5, d = 5.

1. Small squeeze (1 %): linear plane-strain elasticity of a cylinder of radius
   R between two rigid flat plates, force P per unit length on each plate
   (Johnson, Contact Mechanics, 1985, section 5.6): Hertz half-width
       a = sqrt(4 P R / (pi E*)),   E* = E / (1 - nu^2)  (rigid plate),
   peak pressure p0 = 2 P / (pi a), and the decrease of the diameter
       delta = 2 P (1 - nu^2) / (pi E) (2 ln(4 R / a) - 1)
   (each contact contributes half).  The squeeze c gives delta = c d; P_lin
   solves the last equation.  Checked: |F / P_lin - 1| < 1.5 %, b and pmax
   within 5 % of a and p0 (the finite-strain solution at 1 % is not linear:
   the contact width is a/R = 0.08 of the radius).
2. Lindley's empirical O-ring formula, force per unit length of seal
       F / L = E d (1.25 c^1.5 + 50 c^6),
   as a plausibility band: finite-element results read 0.65 to 1.6 times it.
"""
import csv
import math
import os
import sys

MU, K, R = 1.0, 1000.0, 2.5
D = 2 * R
E = 9 * K * MU / (3 * K + MU)
NU = (3 * K - 2 * MU) / (2 * (3 * K + MU))


def linear(c):
    """(P, a, p0) of the linear 2D solution at squeeze c."""
    delta = c * D

    def approach(P):
        a = math.sqrt(4 * P * R * (1 - NU ** 2) / (math.pi * E))
        return 2 * P * (1 - NU ** 2) / (math.pi * E) * (2 * math.log(4 * R / a) - 1)

    lo, hi = 1e-12, 10.0
    for _ in range(200):                    # approach(P) increases with P here (a << R)
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if approach(mid) < delta else (lo, mid)
    P = math.sqrt(lo * hi)
    a = math.sqrt(4 * P * R * (1 - NU ** 2) / (math.pi * E))
    return P, a, 2 * P / (math.pi * a)


def lindley(c):
    return E * D * (1.25 * c ** 1.5 + 50 * c ** 6)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                             "reference.csv")
    with open(path) as f:
        ref = {float(r["squeeze"]): r for r in csv.DictReader(f)}
    ok = True
    print(f"E = {E:.6g} MPa, nu = {NU:.6g}")
    r = ref[0.01]
    F, b, p = float(r["F_per_length_N_per_mm"]), float(r["half_width_mm"]), float(r["p_max_MPa"])
    P, a, p0 = linear(0.01)
    checks = [("F / P_lin", F / P, 0.015), ("b / a", b / a, 0.05), ("pmax / p0", p / p0, 0.05)]
    print(f"1 %: linear P = {P:.6g} N/mm, a = {a:.5g} mm, p0 = {p0:.5g} MPa; "
          f"reference F = {F:.6g}, b = {b:.5g}, pmax = {p:.5g}")
    for name, v, tol in checks:
        good = abs(v - 1) < tol
        ok = ok and good
        print(f"  {name} = {v:.5f} ({'ok' if good else 'FAIL'}: within {tol:.1%})")
    for c in (0.1, 0.2, 0.3):
        F = float(ref[c]["F_per_length_N_per_mm"])
        L = lindley(c)
        good = 0.65 <= F / L <= 1.6
        ok = ok and good
        print(f"{c:.0%}: F = {F:.6g} N/mm, Lindley {L:.5g} N/mm, ratio {F / L:.3f} ({'ok' if good else 'FAIL'}: 0.65-1.6)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
