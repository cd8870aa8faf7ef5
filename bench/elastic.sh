#!/bin/sh
# bench/elastic.sh [REPEATS]: plain plane-strain elasticity (a clamped square,
# MESH rect tri3, traction on top) at about 1e4, 1e5 and 1e6 dofs.  Prints per
# size the median over REPEATS runs (default 3) of each phase's time, the peak
# memory, and the ratios assemble/factor and total/factor.
# Targets (issue): at 1e6 dofs assemble < 0.25 factor, total < 2 factor.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=$(mktemp -d "${TMPDIR:-/tmp}/c2d-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
. "$top/bench/decks.sh"
. "$top/bench/common.sh"
printf '%-9s %9s %7s %8s %8s %8s %8s %8s %8s %9s %8s %8s\n' n dofs mesh assemble factor recover output total memMB \
  nnzL asm/fac tot/fac
for n in 70 223 707; do
  plate_deck "$work/plate.deck" "$n"
  i=0
  while [ $i -lt "$reps" ]; do
    "$prog" -q -o "$work/r$i" "$work/plate.deck"
    i=$((i + 1))
  done
  get() { for s in "$work"/r*/plate.summary; do awk -v k="$1" '$1 == k {print $2}' "$s"; done | median; }
  dofs=$(get dofs); m=$(get time_mesh); a=$(get time_assemble); f=$(get time_factor)
  r=$(get time_recover); o=$(get time_output); t=$(get time_total); mem=$(get memory_peak_mb); nz=$(get factor_nnz)
  awk -v n="$n" -v d="$dofs" -v m="$m" -v a="$a" -v f="$f" -v r="$r" -v o="$o" -v t="$t" -v mem="$mem" -v nz="$nz" \
    'BEGIN {printf "%-9s %9d %7.3f %8.3f %8.3f %8.3f %8.3f %8.3f %8.0f %9.3g %8.3f %8.3f\n", n"x"n, d, m, a, f, r, o, t, mem, nz, a/f, t/f}'
  rm -rf "$work"/r*
done
echo "(medians of $reps runs; seconds; memMB = peak resident memory; BLAS: $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 | sed 's|.*/\([^/]*\)/libblas.so.3|\1|'))"
