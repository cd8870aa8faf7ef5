#!/bin/sh
# studies/cattaneo-force.sh [PROGRAM]: the Cattaneo-Mindlin scene under force
# control (tests/effects/force_control/cattaneo_force.deck) run once, its
# shear and pressure profiles against the closed forms printed with the
# measured errors, and plotted into doc/img/cattaneo_force.png (gnuplot).
# Run from the repository root; the data stay in a temporary folder.
set -eu
prog=${1:-bin/contact2d}
prog=$(cd "$(dirname "$prog")" && pwd)/$(basename "$prog")
top=$(pwd)
out=$(mktemp -d "${TMPDIR:-/tmp}/cattaneo-force.XXXXXX")
(cd tests/effects/force_control && "$prog" -q -o "$out" cattaneo_force.deck)
python3 - "$out" <<'PY'
import math, sys
out = sys.argv[1]
E, nu, mu, R, P, Q, hc = 200000.0, 0.3, 0.5, 1.0, 400.0, 100.0, 0.005
a = math.sqrt(4 * P * R * 2 * (1 - nu**2) / (math.pi * E)); p0 = 2 * P / (math.pi * a)
c = a * math.sqrt(1 - Q / (mu * P))
def q_cm(x):
    x = abs(x)
    if x >= a: return 0.0
    v = mu * p0 * math.sqrt(1 - (x / a)**2)
    return v - mu * p0 * (c / a) * math.sqrt(1 - (x / c)**2) if x < c else v
rows = []
with open(f"{out}/cattaneo_force_contact.csv") as f:
    head = f.readline().strip().split(",")
    for line in f:
        r = dict(zip(head, line.strip().split(",")))
        if r["status"] not in ("", "-1"):
            rows.append((float(r["x"]), float(r["pressure"]), abs(float(r["shear"])), int(float(r["friction_state"]))))
rows.sort()
with open(f"{out}/nodes.dat", "w") as f:
    for x, p, s, st in rows:
        f.write(f"{x / a} {p / p0} {s / (mu * p0)} {st}\n")
with open(f"{out}/exact.dat", "w") as f:
    for i in range(-400, 401):
        x = 1.2 * a * i / 400
        p = p0 * math.sqrt(max(0.0, 1 - (x / a)**2))
        f.write(f"{x / a} {p / p0} {q_cm(x) / (mu * p0)}\n")
stick = [x for x, p, s, st in rows if st == 1 and p > 0]
slip = [x for x, p, s, st in rows if st == 2 and p > 0]
inner = [(x, s) for x, p, s, st in rows if abs(x) < c - hc]
print(f"a = {a:.5f}  p0 = {p0:.2f}  c = {c:.5f} (c/a = {c / a:.4f})  hc = {hc}")
print(f"peak pressure {max(p for _, p, _, _ in rows):.2f} ({(max(p for _, p, _, _ in rows) / p0 - 1) * 100:+.3f} %)")
print(f"stick nodes up to |x| = {max(abs(x) for x in stick):.4f}, slip from |x| = {min(abs(x) for x in slip):.4f}")
print(f"stick-zone shear, max |q - q_exact| / (mu p0) = {max(abs(s - q_cm(x)) for x, s in inner) / (mu * p0):.4f}")
l2 = math.sqrt(sum((s - q_cm(x))**2 for x, _, s, _ in rows) / sum(q_cm(x)**2 for x, _, _, _ in rows))
print(f"nodal shear, relative L2 error {l2:.4f}")
PY
if gnuplot -e 'set terminal' 2>&1 | grep -q pngcairo; then
  term='set terminal pngcairo size 900,560 enhanced font "Sans,11" linewidth 1.5'
else
  term='set terminal png size 900,560'
fi
gnuplot <<GP
$term
set output "$top/doc/img/cattaneo_force.png"
set grid
set key top right box opaque
set xlabel "x / a"
set ylabel "traction / (mu p0), pressure / p0"
set xrange [-1.3:1.3]
set yrange [0:1.15]
set title "Cattaneo-Mindlin under force control: P = 400, Q = 0.5 mu P, a/h = 13.6"
plot "$out/exact.dat" using 1:3 with lines lc rgb "#1f77b4" title "shear q(x), closed form", \
     "$out/nodes.dat" using 1:(\$4 == 1 ? \$3 : 1/0) with points pt 7 ps 0.9 lc rgb "#1f77b4" title "shear, sticking nodes", \
     "$out/nodes.dat" using 1:(\$4 == 2 ? \$3 : 1/0) with points pt 5 ps 0.9 lc rgb "#d62728" title "shear, slipping nodes", \
     "$out/exact.dat" using 1:2 with lines dt 2 lc rgb "#555555" title "pressure, Hertz", \
     "$out/nodes.dat" using 1:2 with points pt 6 ps 0.7 lc rgb "#555555" title "pressure"
GP
echo "wrote doc/img/cattaneo_force.png (data in $out)"
