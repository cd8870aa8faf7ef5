#!/bin/sh
# bench/estimate.sh [REPEATS]: what the error estimate (ESTIMATE, on by
# default) costs.  Each deck runs with ESTIMATE on and with ESTIMATE off, in
# turn, REPEATS times (default 9); prints the medians of time_estimate and of
# time_total both ways, and their ratios to the plain run (ESTIMATE off):
# time_estimate / total(off), the estimate's own share, and total(on) /
# total(off) - 1, what the user pays.  Decks (bench/decks.sh):
#   hertz_1e5       Hertz H on graded gmsh meshes, P1, about 9e4 dofs
#   hertz_p2        the same meshes at hc 0.002 made quadratic (gmsh -order 2)
#   signorini_1e5   Signorini S, MESH rect 500 x 50 and 400 x 60, Q1
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/common.sh"
. "$top/bench/decks.sh"
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-9}
work=${BENCH_OUT:-$top/bench/out/estimate}
mkdir -p "$work"
hertz_deck "$work/hertz_1e5.deck" hertz_1e5 0.001 0.04
for part in block disk; do
  [ -f "$work/p2_$part.msh" ] || gmsh -2 -order 2 -format msh41 -v 1 -setnumber hc 0.002 -setnumber hf 0.08 \
    "$top/bench/geo/hertz_${part}_graded.geo" -o "$work/p2_$part.msh"
done
hertz_deck "$work/hertz_p2.deck" p2 0.002 0.08
signorini_deck "$work/signorini_1e5.deck" 500 50 400 60
printf '%-16s %8s %12s %12s %12s %10s %10s\n' deck dofs time_estimate total_on total_off est/off on/off-1
for name in hertz_1e5 hertz_p2 signorini_1e5; do
  deck=$work/$name.deck
  grep -v '^ESTIMATE' "$deck" > "$work/${name}_off.deck"
  echo "ESTIMATE off" >> "$work/${name}_off.deck"
  rm -f "$work/$name.t" "$work/$name.on" "$work/$name.off"
  i=0
  while [ "$i" -lt "$reps" ]; do
    "$prog" -q -o "$work/out" "$deck"
    awk '$1 == "time_estimate" {print $2}' "$work/out/$name.summary" >> "$work/$name.t"
    awk '$1 == "time_total" {print $2}' "$work/out/$name.summary" >> "$work/$name.on"
    "$prog" -q -o "$work/out" "$work/${name}_off.deck"
    awk '$1 == "time_total" {print $2}' "$work/out/${name}_off.summary" >> "$work/$name.off"
    i=$((i + 1))
  done
  dofs=$(awk '$1 == "dofs" {print $2}' "$work/out/$name.summary")
  t=$(median < "$work/$name.t"); on=$(median < "$work/$name.on"); off=$(median < "$work/$name.off")
  printf '%-16s %8s %12.4g %12.4g %12.4g %10.3f %10.3f\n' "$name" "$dofs" "$t" "$on" "$off" \
    "$(echo "$t $off" | awk '{print $1 / $2}')" "$(echo "$on $off" | awk '{print $1 / $2 - 1}')"
done
