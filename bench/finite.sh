#!/bin/sh
# bench/finite.sh [HC...]: what a load step of CONTACT sliding=finite costs
# against a step of small sliding and against a factorization, on two drags
# in 10 steps with OUTPUT steps=all:
#   rigid   tests/rigid/finite: a rigid cylinder R = 10 pressed by a FORCE
#           P = 10000 on a block 200 x 100 (its vertical motion an equality
#           of the LCP), elements hc along its path;
#   bodies  tests/contact/finite: a deformable half-disc roller R = 10 on the
#           same block, pressed and dragged by its top (prescribed motion),
#           elements hc along the path on both bodies; every node of the two
#           contact boundaries is a contact dof.
# For each, two runs of the same deck:
#   finite  the drag d = 3.8 with sliding=finite (every step: geometry
#           updates, each a rebuild of the rows, a condensation, a solve and
#           an LCP);
#   small   the same deck with sliding=small and d = hc/2 (within the
#           sliding monitor): every step one solve and one LCP on the W of
#           the final step.
# Prints per case the dofs, the contact rows, the factor phase (one
# factorization), the lcp phase per step for both (the steps' whole cost),
# and for finite the updates and their split: rebuild, condensation, LCP per
# update.  Default HC: 0.05 0.02.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
work=${BENCH_OUT:-$top/bench/out/finite}
mkdir -p "$work"
[ $# -gt 0 ] || set -- 0.05 0.02
printf '%-7s %-6s %7s %5s %8s %12s %12s %8s %10s %10s %10s\n' case hc dofs rows factor small/step finite/step updates \
  rebuild/u cond/u lcp/u
for case in rigid bodies; do
  case $case in
    rigid) src=$top/tests/rigid/finite ;;
    bodies) src=$top/tests/contact/finite ;;
  esac
  cp "$src"/*.geo "$work/"
  sed 's/sliding=finite/sliding=small/' "$src/drag.deck" > "$work/small.deck"
  cp "$src/drag.deck" "$work/finite.deck"
  for hc in "$@"; do
    "$prog" -o "$work/s" -D hc="$hc" -D d="$(echo "$hc / 2" | bc -l)" "$work/small.deck" > "$work/small.log"
    "$prog" -o "$work/f" -D hc="$hc" "$work/finite.deck" > "$work/finite.log"
    awk -v hc="$hc" -v case="$case" '
      FNR == 1 { file++ }
      /^sizes/ { dofs = $2; rows = $6 }
      /^factor  / && NF == 2 { if (file == 1) factor = $2 }
      /^lcp  / && NF == 2 { lcp[file] = $2 }
      /^finite   [0-9]+ geometry updates/ { up = $2; rb = $9; cd = $12; lp = $15 }
      END {
        printf "%-7s %-6s %7d %5d %8.4f %12.4f %12.4f %8d %10.2e %10.2e %10.2e\n", case, hc, dofs, rows, factor,
          lcp[1] / 10, lcp[2] / 10, up, rb / up, cd / up, lp / up
      }' "$work/small.log" "$work/finite.log"
  done
done
