#!/usr/bin/python3
"""Pressure error of a Hertz H solution against the closed form.

One definition for every code.  From the code's own computed load P (the
reaction on the disk's top edge, per unit thickness):
    1/E* = 2 (1 - nu^2) / E,  a = sqrt(4 P R / (pi E*)),  p0 = 2 P / (pi a),
    p_H(x) = p0 sqrt(1 - x^2 / a^2),
and over the slave (block top) nodes with |x| < a:
    err = sqrt( sum (p_i - p_H(x_i))^2 / sum p_H(x_i)^2 ).

A profile file (written by each runner) holds lines "# key value" (at least
"# P value" and "# dofs N") and then one "x p" pair per block-top node.

    hertz_err.py FILE...   prints "file dofs P a p0 err" per file
"""
import math
import sys

E, NU, R = 200000.0, 0.3, 1.0
ESTAR = 1.0 / (2.0 * (1.0 - NU * NU) / E)


def hertz(P):
    """Half-width a and peak pressure p0 for the load P (per unit length)."""
    a = math.sqrt(4.0 * abs(P) * R / (math.pi * ESTAR))
    return a, 2.0 * abs(P) / (math.pi * a)


def l2err(xs, ps, P):
    """Relative L2 pressure error over the nodes with |x| < a."""
    a, p0 = hertz(P)
    num = den = 0.0
    for x, p in zip(xs, ps):
        if abs(x) < a:
            ph = p0 * math.sqrt(max(0.0, 1.0 - x * x / (a * a)))
            num += (p - ph) ** 2
            den += ph ** 2
    return math.sqrt(num / den) if den > 0.0 else float("nan")


def write_profile(path, xs, ps, **meta):
    """Write a profile file: '# key value' lines, then 'x p' rows sorted by x."""
    with open(path, "w") as f:
        for k, v in meta.items():
            f.write(f"# {k} {v!r}\n" if isinstance(v, float) else f"# {k} {v}\n")
        for x, p in sorted(zip(xs, ps)):
            f.write(f"{x!r} {p!r}\n")


def read_profile(path):
    """Return (meta dict of strings, xs, ps) from a profile file."""
    meta, xs, ps = {}, [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "#":
                if len(w) >= 3:
                    meta[w[1]] = w[2]
            else:
                xs.append(float(w[0]))
                ps.append(float(w[1]))
    return meta, xs, ps


def evaluate(path):
    """(dofs, P, a, p0, err) of a profile file."""
    meta, xs, ps = read_profile(path)
    P = float(meta["P"])
    a, p0 = hertz(P)
    return int(meta.get("dofs", 0)), P, a, p0, l2err(xs, ps, P)


if __name__ == "__main__":
    for fn in sys.argv[1:]:
        d, P, a, p0, e = evaluate(fn)
        print(f"{fn} {d} {P:.6g} {a:.6g} {p0:.6g} {e:.4%}")
