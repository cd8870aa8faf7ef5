#!/bin/sh
# bench/pressure_estimate.sh: how far to trust `estimate pressure` (module
# pressure_recovery through run_estimate).  Prints, for each run, the true
# relative L2 error of the contact pressure, the estimate and their ratio,
# the effectivity:
#   - Hertz H (input/hertz.deck, the box-field meshes of
#     tests/estimate/hertz), P1 and P2 (order=2), hc from 0.07 to 0.005, a/h =
#     1 to 14 for the half-width a = 0.070, the true error against the graded
#     P2 reference tests/estimate/hertz/reference_contact.csv (PROVENANCE);
#   - the axisymmetric press fit of equal lengths of tests/estimate/press_fit
#     (the hub's bore or the shaft as the slave), h = 0.1, 0.05, 0.025, P1 and
#     P2, against Lame's uniform pressure.
# The figures and their history are in doc/theory.md ("Error estimate").
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
work=${BENCH_OUT:-$top/bench/out/pressure_estimate}
mkdir -p "$work"
cp "$top"/tests/estimate/hertz/hertz_block.geo "$top"/tests/estimate/hertz/hertz_disk.geo \
   "$top"/tests/estimate/press_fit/ring.geo "$work"/
CONTACT2D=$prog TOP=$top WORK=$work exec python3 - <<'PY'
import os, subprocess, sys
top, work, prog = os.environ["TOP"], os.environ["WORK"], os.environ["CONTACT2D"]
sys.path.insert(0, os.path.join(top, "tests", "lib"))
from c2dcheck import contact_table
from pressure_error import profile, l2_difference
from energy_error import estimate
from lame import lame, lam, mu


def solve(name, text):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as h:
        h.write(text)
    subprocess.run([prog, "-q", "-o", os.path.join(work, "out"), path], check=True)
    return (estimate(os.path.join(work, "out", name + ".summary"), "pressure", 1),
            contact_table(os.path.join(work, "out", name + "_contact.csv")))


print(f"{'case':28s} {'a/h':>5s} {'true':>10s} {'estimate':>10s} {'effectivity':>11s}")
ref = profile(contact_table(os.path.join(top, "tests/estimate/hertz/reference_contact.csv")))
with open(os.path.join(top, "input/hertz.deck")) as h:
    hertz = h.read()
for order in (1, 2):
    for hc in ("0.07", "0.06", "0.05", "0.042", "0.035", "0.03", "0.025", "0.02", "0.0175", "0.014", "0.01",
               "0.0085", "0.007", "0.005"):
        name = f"hertz_p{order}_{hc}"
        est, rows = solve(name, hertz.replace("hc=0.01", f"hc={hc}").replace("hf=0.5\n", f"hf=0.5 order={order}\n"))
        true = l2_difference(profile(rows), ref)
        print(f"{'hertz P%d hc=%s' % (order, hc):28s} {0.07 / float(hc):5.1f} {true:10.3e} {est:10.3e} {est / true:11.3f}")
with open(os.path.join(top, "tests/estimate/press_fit/press_fit.deck")) as h:
    fit = h.read()
a, b = 0.999, 1.0
p_shaft = -2 * (lam + mu) * lame(b, a, 2.0)[0]
for slave, p in (("hub", p_shaft * b / a), ("shaft", p_shaft)):
    text = fit if slave == "hub" else fit.replace("slave=hub:inner master=shaft:outer", "slave=shaft:outer master=hub:inner")
    for order in (1, 2):
        for size in ("0.1", "0.05", "0.025"):
            name = f"fit_{slave}_p{order}_{size}"
            est, rows = solve(name, text.replace("PARAMETER h=0.1 order=1", f"PARAMETER h={size} order={order}"))
            rows = sorted((r for r in rows if r["status"] is not None and r["status"] >= 0), key=lambda r: r["y"])
            num = den = 0.0
            for r0, r1 in zip(rows, rows[1:]):
                dz, d0, d1 = r1["y"] - r0["y"], r0["pressure"] - p, r1["pressure"] - p
                num += dz * (d0 * d0 + d0 * d1 + d1 * d1) / 3
                den += dz * p * p
            true = (num / den) ** 0.5
            print(f"{'fit %s P%d h=%s' % (slave, order, size):28s} {'-':>5s} {true:10.3e} {est:10.3e} {est / true:11.3f}")
PY
