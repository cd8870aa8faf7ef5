#!/bin/sh
# bench/ordering.sh [REPEATS]: where METIS nested dissection starts to pay
# against AMD (approximate minimum degree), the crossover behind
# `SOLVER ordering=auto`.  Three families over sizes from 5e4 to 1e6 dofs:
# plate (one clamped square, no contact, MESH rect), signorini (two MESH rect
# blocks, the contact dofs ordered last) and hertz (graded gmsh meshes, as in
# bench/contact.sh).  Each case runs with ordering=amd and ordering=metis;
# prints the medians over REPEATS runs (default 3) of the ordering time (the
# analysis), the whole factor phase and the whole run, nnz(L), and the ratio
# total(metis) / total(amd): above 1, AMD is the faster choice.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/ordering}
mkdir -p "$work"
. "$top/bench/decks.sh"
. "$top/bench/common.sh"

for o in amd metis; do
  for n in 160 223 316 447 707; do plate_deck "$work/plate_${n}_$o.deck" "$n" "SOLVER ordering=$o"; done
  signorini_deck "$work/signorini_1_$o.deck" 500 50 400 60 "SOLVER ordering=$o"
  signorini_deck "$work/signorini_2_$o.deck" 700 70 560 85 "SOLVER ordering=$o"
  signorini_deck "$work/signorini_4_$o.deck" 1000 100 800 120 "SOLVER ordering=$o"
  signorini_deck "$work/signorini_10_$o.deck" 1580 158 1265 190 "SOLVER ordering=$o"
  hertz_deck "$work/hertz_1_$o.deck" hertz_1 0.001 0.04 "SOLVER ordering=$o"
  hertz_deck "$work/hertz_3_$o.deck" hertz_3 0.001 0.02 "SOLVER ordering=$o"
  hertz_deck "$work/hertz_10_$o.deck" hertz_10 0.001 0.0095 "SOLVER ordering=$o"
done
cases="plate_160 plate_223 plate_316 plate_447 plate_707 signorini_1 signorini_2 signorini_4 signorini_10 hertz_1 hertz_3 hertz_10"

printf '%-13s %8s | %9s %9s | %7s %7s | %7s %7s | %7s %7s | %11s\n' case dofs nnzL_amd nnzL_metis \
  ord_amd ord_met fac_amd fac_met tot_amd tot_met metis/amd
for c in $cases; do
  for o in amd metis; do
    i=0
    while [ $i -lt "$reps" ]; do
      "$prog" -q -o "$work/run_${o}_$i" "$work/${c}_$o.deck"
      i=$((i + 1))
    done
  done
  get() { for s in "$work"/run_"$1"_*/"${c}_$1.summary"; do awk -v k="$2" '$1 == k {print $2}' "$s"; done | median; }
  awk -v c="$c" -v d="$(get amd dofs)" -v na="$(get amd factor_nnz)" -v nm="$(get metis factor_nnz)" \
      -v oa="$(get amd time_ordering)" -v om="$(get metis time_ordering)" \
      -v fa="$(get amd time_factor)" -v fm="$(get metis time_factor)" \
      -v ta="$(get amd time_total)" -v tm="$(get metis time_total)" \
      'BEGIN {printf "%-13s %8d | %9.3g %9.3g | %7.3f %7.3f | %7.3f %7.3f | %7.3f %7.3f | %11.3f\n",
              c, d, na, nm, oa, om, fa, fm, ta, tm, tm / ta}'
  rm -rf "$work"/run_*
done
echo "(medians of $reps runs, seconds; ord = time_ordering, fac = time_factor (ordering + numeric), tot = time_total;"
echo " threads: OMP_NUM_THREADS=${OMP_NUM_THREADS:-all}, OpenBLAS: ${OPENBLAS_NUM_THREADS:-all})"
