#!/bin/sh
# bench/contact.sh [REPEATS]: the cost of contact at scale.  Hertz (graded
# gmsh meshes, 600 slave nodes on the contact line) and Signorini (MESH rect,
# 501 and 801 slave nodes) at about 1e5 and 1e6 dofs.  Each case runs with
# CONTACT and, as the baseline, the same stiffness without CONTACT (default
# ordering, auto).  Prints medians over REPEATS runs (default 3) and the
# ratios of the targets:
#   overhead = (condense + lcp + recover) / factor              target <= 0.3
#   whole    = total(contact) / (factor + solve)(baseline)      target <= 1.3
#   base     = total(baseline) / (factor + solve)(baseline)     (for reference:
#              what reading, assembling and writing add to a run without contact)
#   memory   = peak resident / CHOLMOD factor memory             target <= 1.5
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/contact}
mkdir -p "$work"
. "$top/bench/decks.sh"
. "$top/bench/common.sh"

hertz_deck "$work/hertz_1e5.deck" hertz_1e5 0.001 0.04
hertz_deck "$work/hertz_1e6.deck" hertz_1e6 0.001 0.0095
signorini_deck "$work/signorini_1e5.deck" 500 50 400 60
signorini_deck "$work/signorini_1e6.deck" 800 400 600 300

printf '%-14s %8s %5s %6s %7s %8s %8s %7s %7s %8s %8s %7s | %8s %9s %8s %6s\n' case dofs nodes active assemble factor \
  condense lcp recover total memMB fmemMB overhead whole memory base
for c in hertz_1e5 signorini_1e5 hertz_1e6 signorini_1e6; do
  grep -v '^CONTACT' "$work/$c.deck" > "$work/${c}_base.deck"
  i=0
  while [ $i -lt "$reps" ]; do
    "$prog" -q -o "$work/run$i" "$work/$c.deck"
    "$prog" -q -o "$work/run$i" "$work/${c}_base.deck"
    i=$((i + 1))
  done
  get() { for s in "$work"/run*/"$1.summary"; do awk -v k="$2" '$1 == k {print $2}' "$s"; done | median; }
  awk -v c="$c" -v d="$(get "$c" dofs)" -v n="$(get "$c" contact_nodes)" -v act="$(get "$c" active_nodes)" \
      -v a="$(get "$c" time_assemble)" -v f="$(get "$c" time_factor)" -v co="$(get "$c" time_condense)" \
      -v l="$(get "$c" time_lcp)" -v r="$(get "$c" time_recover)" -v t="$(get "$c" time_total)" \
      -v m="$(get "$c" memory_peak_mb)" -v fm="$(get "$c" factor_memory_mb)" \
      -v bf="$(get "${c}_base" time_factor)" -v bs="$(get "${c}_base" time_solve)" \
      -v bt="$(get "${c}_base" time_total)" \
      'BEGIN {printf "%-14s %8d %5d %6d %7.3f %8.3f %8.3f %7.3f %7.3f %8.3f %8.0f %7.0f | %8.3f %9.3f %8.3f %6.3f\n",
              c, d, n, act, a, f, co, l, r, t, m, fm, (co + l + r) / f, t / (bf + bs), m / fm, bt / (bf + bs)}'
  rm -rf "$work"/run*
done
echo "(medians of $reps runs, seconds; baseline = the same bodies without CONTACT)"
