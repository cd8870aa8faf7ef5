#!/bin/sh
# bench/adapt.sh [REPEATS]: what ADAPT and `estimate cost_to_halve` deliver
# (doc/accuracy-cost.md, "Adaptive meshes").  Medians of REPEATS runs
# (default 3) of cpu_total, the run's CPU seconds with gmsh's included
# (--no-mesh-cache: every run meshes its .geo, as the first run of a deck
# does; a repeated run would read the mesh cache).
#  1. Hertz (input/hertz.deck, its .geo: size hc near the contact, hf away):
#     the uniform P2 meshes around 1 % true pressure error (hc = 0.005 reaches
#     it, hc = 0.002 is 2.5 times finer) against ADAPT from hc = 0.05 to a 1 %
#     pressure estimate; P1 uniform at hc = 0.005 and 0.0025 against ADAPT to
#     2 % and 1 %; the true error against
#     tests/estimate/hertz/reference_contact.csv (tests/lib/pressure_error.py).
#  2. The flat punch (tests/rigid/punch/punch.deck, a force P on a rigid die;
#     P1, a rigid obstacle takes linear slaves only): a series refined
#     everywhere (hc near the die, hf = 12.5 hc away from it) against
#     ADAPT to 8, 4 and 2 % in energy, each with its estimate and its true
#     energy error, sqrt(|U_ref - U_h| / U_ref) from the strain energies (a
#     force-driven problem whose contact zone is the die's whole face: the
#     energy error is the energies' difference), U_ref extrapolated from the
#     three finest uniform meshes (Aitken's delta squared: their sizes halve,
#     so their energies converge geometrically).  The die's sides open at 45
#     degrees: with vertical sides the block's surface beside a corner meets
#     the side edge-on on fine meshes, which small sliding refuses.
#  3. cost_to_halve: three runs' predicted CPU time and dofs against those of
#     the mesh ADAPT reaches at half their energy error (the last `adapt` line).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/common.sh"
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/adapt}
ref=$top/tests/estimate/hertz/reference_contact.csv
mkdir -p "$work"
cp "$top/input/hertz_block.geo" "$top/input/hertz_disk.geo" "$work/"

last_adapt() { awk '$1 == "adapt" {d = $4} END {print d}' "$1"; }
# run NAME (bench/common.sh): REPEATS runs of $work/NAME.deck; NAME.cpu holds the median cpu_total
hertz() {   # hertz NAME HC ORDER [STATEMENT]
  sed -e "s/hc=0.01 hf=0.5/hc=$2 hf=0.5 order=$3/" "$top/input/hertz.deck" > "$work/$1.deck"
  [ -z "${4:-}" ] || echo "$4" >> "$work/$1.deck"
}
punch() {   # punch NAME HC ORDER [STATEMENT]: hf = 12.5 hc (hf = 0.5 at most), the whole block refined with hc
  hf=$(echo "$2" | awk '{h = 12.5 * $1; print (h > 0.5) ? 0.5 : h}')
  sed -e "s|file=../../../input/hertz_block.geo hc=0.01 hf=0.5|file=hertz_block.geo hc=$2 hf=$hf order=$3|" \
    -e 's/points=${-a}:0.2,${-a}:0,${a}:0,${a}:0.2/points=${-a-0.2}:0.2,${-a}:0,${a}:0,${a+0.2}:0.2/' \
    "$top/tests/rigid/punch/punch.deck" > "$work/$1.deck"
  [ -z "${4:-}" ] || echo "$4" >> "$work/$1.deck"
}

echo "1. Hertz, contact pressure (true error against the fine P2 reference)"
printf '%-22s %9s %11s %12s %10s\n' run dofs estimate% true% cpu_s
hertz uniform_p2_0.005 0.005 2
hertz uniform_p2_0.002 0.002 2
hertz adapt_p2_1 0.05 2 "ADAPT target=0.01 quantity=pressure"
hertz uniform_p1_0.005 0.005 1
hertz uniform_p1_0.0025 0.0025 1
hertz adapt_p1_2 0.05 1 "ADAPT target=0.02 quantity=pressure"
hertz adapt_p1_1 0.05 1 "ADAPT target=0.01 quantity=pressure"
for name in uniform_p2_0.005 uniform_p2_0.002 adapt_p2_1 uniform_p1_0.005 uniform_p1_0.0025 adapt_p1_2 adapt_p1_1; do
  run "$name"
  s=$work/out/$name.summary
  printf '%-22s %9s %11.4f %12s %10.3f\n' "$name" "$(key "$s" dofs)" \
    "$(awk '$1 == "estimate" && $2 == "pressure" {print 100 * $4}' "$s")" \
    "$(python3 "$top/tests/lib/pressure_error.py" "$ref" "$work/out/${name}_contact.csv")" "$(cat "$work/$name.cpu")"
done
awk 'NR == FNR {u = $1; next} {printf "P2 at 1 %%: adaptive CPU / uniform (hc = 0.005) CPU = %.3f\n", $1 / u}' \
  "$work/uniform_p2_0.005.cpu" "$work/adapt_p2_1.cpu"
awk 'NR == FNR && $1 == "dofs" {u = $2; next} $1 == "dofs" {printf "P2 at 1 %%: adaptive dofs / uniform dofs = %.3f\n", $2 / u}' \
  "$work/out/uniform_p2_0.005.summary" "$work/out/adapt_p2_1.summary"

echo
echo "2. Flat punch, energy norm (true error from the strain energies)"
series="punch_p1_0.04:0.04:1 punch_p1_0.02:0.02:1 punch_p1_0.01:0.01:1 punch_p1_0.005:0.005:1 punch_p1_0.0025:0.0025:1"
for item in $series; do
  name=${item%%:*}; rest=${item#*:}
  punch "$name" "${rest%%:*}" "${rest#*:}"
done
punch punch_adapt_10 0.05 1 "ADAPT target=0.1"
punch punch_adapt_7 0.05 1 "ADAPT target=0.07"
for item in $series; do run "${item%%:*}"; done
uref=$(for h in 0.01 0.005 0.0025; do key "$work/out/punch_p1_$h.summary" energy; done |
  awk '{u[NR] = $1} END {d1 = u[2] - u[1]; d2 = u[3] - u[2]; print u[3] - d2 * d2 / (d2 - d1)}')
echo "U_ref = $uref (Aitken, from the energies at hc = 0.01, 0.005, 0.0025)"
printf '%-22s %9s %11s %12s %12s %10s\n' run dofs estimate% true% effectivity cpu_s
for item in $series punch_adapt_10 punch_adapt_7; do
  name=${item%%:*}
  [ -f "$work/$name.cpu" ] && [ "$work/$name.cpu" -nt "$work/$name.deck" ] || run "$name"
  s=$work/out/$name.summary
  est=$(awk '$1 == "estimate" && $2 == "energy" {print 100 * $3}' "$s")
  true=$(awk -v r="$uref" '$1 == "energy" {d = r - $2; if (d < 0) d = -d; print 100 * sqrt(d / r)}' "$s")
  printf '%-22s %9s %11.4f %12.4f %12.3f %10.3f\n' "$name" "$(key "$s" dofs)" "$est" "$true" \
    "$(echo "$est $true" | awk '{print $1 / $2}')" "$(cat "$work/$name.cpu")"
done

echo
echo "3. cost_to_halve: predicted against the mesh ADAPT reaches at half the energy error"
printf '%-14s %12s %10s %12s %10s %10s %10s\n' problem pred_cpu cpu pred_dofs dofs cpu_ratio dofs_ratio
hertz c_hertz_p1 0.02 1
hertz c_hertz_p2 0.05 2
punch c_punch_p1 0.04 1
for name in c_hertz_p1 c_hertz_p2 c_punch_p1; do
  runs "$name" "$work/$name.p" '$1 == "estimate" && $2 == "cost_to_halve" {print $3, $4}'
  half=$(awk '$1 == "estimate" && $2 == "energy" {print $3 / 2}' "$work/out/$name.summary")
  { cat "$work/$name.deck"; echo "ADAPT target=$half"; } > "$work/${name}_half.deck"
  runs "${name}_half" "$work/$name.m" '$1 == "adapt" {c = $8; d = $4} END {print c, d}'
  pc=$(awk '{print $1}' "$work/$name.p" | median); pd=$(awk '{print $2}' "$work/$name.p" | median)
  mc=$(awk '{print $1}' "$work/$name.m" | median); md=$(awk '{print $2}' "$work/$name.m" | median)
  printf '%-14s %12.3f %10.3f %12.0f %10.0f %10.3f %10.3f\n' "$name" "$pc" "$mc" "$pd" "$md" \
    "$(echo "$mc $pc" | awk '{print $1 / $2}')" "$(echo "$md $pd" | awk '{print $1 / $2}')"
done
