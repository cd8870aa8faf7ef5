#!/bin/sh
# bench/compare.sh OLD NEW DECK [REPEATS]: two builds of contact2d on one deck,
# run in turn (old, new, old, new, ...) so that the machine's drift falls on
# both alike; prints the medians over REPEATS runs (default 5) of every
# time_* key of the summary, memory_peak_mb and factor_nnz, and new / old.
# With a deck whose CONTACT lines are removed (DECK_base.deck beside it, made
# here), also the ratio `whole` of bench/contact.sh for each build:
# total(contact) / (factor + solve)(baseline).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/common.sh"
[ $# -ge 3 ] || { echo "usage: bench/compare.sh OLD NEW DECK [REPEATS]" >&2; exit 2; }
old=$1 new=$2 deck=$3 reps=${4:-5}
work=$(mktemp -d "${TMPDIR:-/tmp}/c2d-compare.XXXXXX")
trap 'rm -rf "$work"' EXIT
name=$(basename "$deck" .deck)
base=$(dirname "$deck")/${name}_base.deck
grep -v '^CONTACT' "$deck" > "$base"
keys="time_mesh time_assemble time_factor time_ordering time_assemble_values time_condense time_lcp time_recover time_output time_total time_solve memory_peak_mb factor_nnz"

i=0
while [ $i -lt "$reps" ]; do
  for b in old new; do
    eval prog=\$$b
    for d in "$deck" "$base"; do
      n=$(basename "$d" .deck)
      "$prog" -q -o "$work/out" "$d"
      for k in $keys; do
        awk -v k="$k" '$1 == k {print $2}' "$work/out/$n.summary" >> "$work/$b.$n.$k"
      done
    done
  done
  i=$((i + 1))
done

printf '%-22s %14s %14s %8s\n' "$name (medians of $reps)" old new new/old
for k in $keys; do
  o=$(median < "$work/old.$name.$k"); n=$(median < "$work/new.$name.$k")
  printf '%-22s %14.6g %14.6g %8.3f\n' "$k" "$o" "$n" "$(echo "$n $o" | awk '{print ($2 > 0) ? $1 / $2 : 0}')"
done
for b in old new; do
  t=$(median < "$work/$b.$name.time_total")
  fs=$(paste "$work/$b.${name}_base.time_factor" "$work/$b.${name}_base.time_solve" | awk '{print $1 + $2}' | median)
  bt=$(median < "$work/$b.${name}_base.time_total")
  printf '%s: baseline total %.3f, factor + solve %.3f; whole %.3f\n' "$b" "$bt" "$fs" "$(echo "$t $fs" | awk '{print $1 / $2}')"
done
