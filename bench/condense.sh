#!/bin/sh
# bench/condense.sh [REPEATS]: the Delassus matrix with many contact nodes.
# Signorini S (two MESH rect blocks, flat interface, slave nx = N, master
# nx = 4N/5, ny = 20) for N = 1000 ... 5000 slave nodes, and at 918k dofs
# with 5001 (ny = 50), each with SOLVER condense=solve (every block of L_cc
# by triangular solves) and condense=auto (a block by its inverse where
# inverse_pays says so), run in turn.  Prints medians over REPEATS runs
# (default 3) of time_condense, auto / solve, and the contact overhead
# (condense + lcp + recover) / factor with auto.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/condense}
mkdir -p "$work"
. "$top/bench/decks.sh"
. "$top/bench/common.sh"

printf '%-16s %8s %6s %10s %10s %7s %8s %8s %8s %9s\n' case dofs nodes solve auto ratio factor lcp recover overhead
for c in 1000:20 2000:20 3000:20 5000:20 5000:50; do
  n=${c%:*} ny=${c#*:}
  name=s${n}_ny$ny
  for how in solve auto; do
    signorini_deck "$work/${name}_$how.deck" "$n" "$ny" $((n * 4 / 5)) "$ny" "SOLVER lcp=auto condense=$how"
  done
  i=0
  while [ $i -lt "$reps" ]; do
    for how in solve auto; do "$prog" -q -o "$work/run$i" "$work/${name}_$how.deck"; done
    i=$((i + 1))
  done
  get() { for s in "$work"/run*/"${name}_$1.summary"; do awk -v k="$2" '$1 == k {print $2}' "$s"; done | median; }
  awk -v c="$name" -v d="$(get auto dofs)" -v n="$(get auto contact_nodes)" -v s="$(get solve time_condense)" \
      -v a="$(get auto time_condense)" -v f="$(get auto time_factor)" -v l="$(get auto time_lcp)" \
      -v r="$(get auto time_recover)" \
      'BEGIN {printf "%-16s %8d %6d %10.3f %10.3f %7.3f %8.3f %8.3f %8.3f %9.3f\n", c, d, n, s, a, a / s, f, l, r, (a + l + r) / f}'
  rm -rf "$work"/run*
done
echo "(medians of $reps runs, seconds; ratio = auto / solve; overhead = (condense + lcp + recover) / factor, auto)"
