#!/bin/sh
# bench/vgroove.sh [REPEATS] [NRIM ...]: what the contact solve costs against
# the factorization when the slave is named as users name it.  A disk in a
# rigid V-groove (tests/hard/vgroove/rim.deck, N mm MPa), its whole rim the
# slave (a closed curve, NRIM nodes: 512 and 1024 by default, of which a few
# dozen touch), against the same disk with its two lower quarter arcs named
# as two pairs.  Prints per case the medians over REPEATS runs (default 3)
# of time_factor and time_lcp (seconds, the summary's), their ratio, the LCP
# iterations (the flank forces are tests/hard/vgroove's).  One thread
# (-j 1).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
[ $# -gt 0 ] && shift
sizes=${*:-512 1024}
work=${BENCH_OUT:-$top/bench/out/vgroove}
mkdir -p "$work"
. "$top/bench/common.sh"
cp "$top/tests/hard/vgroove/disk.geo" "$work/"

printf '%-6s %-5s %12s %12s %8s %8s\n' nrim slave time_factor time_lcp lcp/fac iters
for n in $sizes; do
  for slave in rim two; do
    deck=$work/${slave}_$n.deck
    sed -e "s/n=512/n=$n/" "$top/tests/hard/vgroove/rim.deck" > "$deck"
    if [ $slave = two ]; then
      sed -i -e 's/^CONTACT slave=disk:rim master=groove$/CONTACT slave=disk:sw master=groove\nCONTACT slave=disk:se master=groove/' "$deck"
    fi
    : > "$work/f"; : > "$work/l"; : > "$work/i"
    r=0
    while [ $r -lt "$reps" ]; do
      out=$work/out_${slave}_$n
      rm -rf "$out"
      "$prog" -q -j 1 -o "$out" "$deck"
      s=$out/$(basename "$deck" .deck).summary
      awk '$1 == "time_factor" {print $2}' "$s" >> "$work/f"
      awk '$1 == "time_lcp" {print $2}' "$s" >> "$work/l"
      awk '$1 == "lcp_iterations" {print $2}' "$s" >> "$work/i"
      r=$((r + 1))
    done
    f=$(median < "$work/f"); l=$(median < "$work/l"); i=$(median < "$work/i")
    printf '%-6s %-5s %12.4f %12.4f %8.4f %8s\n' "$n" "$slave" "$f" "$l" "$(awk -v l="$l" -v f="$f" 'BEGIN {print l / f}')" "$i"
  done
done
