#!/bin/sh
# bench/cut.sh [REPEATS]: what cutting a large body in two halves factorized
# side by side (SOLVER cut=auto, the default) buys against factorizing it
# whole (cut=off), measured in one run: Hertz at 1e6 dofs (the block seven
# times the disk; METIS) with CONTACT and without, one body of 1e6 dofs (a
# clamped square, MESH rect, METIS), and Hertz at 2.8e5 dofs (the block of
# 230,000 dofs; `ordering=auto` takes AMD there, the halves ordered by CAMD)
# with CONTACT and without.  The two settings run in turn on each
# deck; prints the medians over REPEATS runs (default 3) of the factor phase
# (ordering + numeric factorization), the ordering, the solve (time_solve:
# with contact the two halves of one solve), the whole run and the peak
# memory, and auto / off for each.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
set=${2:-all}
work=${BENCH_OUT:-$top/bench/out/contact}
mkdir -p "$work"
. "$top/bench/decks.sh"
. "$top/bench/common.sh"

for cut in auto off; do
  if [ "$set" = rect ]; then
    signorini_deck "$work/cut_sig_$cut.deck" 460 230 32 16 "SOLVER ordering=metis cut=$cut"
    grep -v '^CONTACT' "$work/cut_sig_$cut.deck" > "$work/cut_sig_base_$cut.deck"
    signorini_deck "$work/cut_sigamd_$cut.deck" 460 230 32 16 "SOLVER ordering=amd cut=$cut"
    grep -v '^CONTACT' "$work/cut_sigamd_$cut.deck" > "$work/cut_sigamd_base_$cut.deck"
    plate_deck "$work/cut_plate450_$cut.deck" 450 "SOLVER ordering=amd cut=$cut"
  else
    hertz_deck "$work/cut_hertz_$cut.deck" hertz_1e6 0.001 0.0095 "SOLVER cut=$cut"
    grep -v '^CONTACT' "$work/cut_hertz_$cut.deck" > "$work/cut_hertz_base_$cut.deck"
    plate_deck "$work/cut_plate_$cut.deck" 707 "SOLVER ordering=metis cut=$cut"
    hertz_deck "$work/cut_hertz3_$cut.deck" hertz_3e5 0.001 0.021 "SOLVER cut=$cut"
    grep -v '^CONTACT' "$work/cut_hertz3_$cut.deck" > "$work/cut_hertz3_base_$cut.deck"
  fi
done
if [ "$set" = rect ]; then
  cases="cut_sig cut_sig_base cut_sigamd cut_sigamd_base cut_plate450"
else
  cases="cut_hertz cut_hertz_base cut_plate cut_hertz3 cut_hertz3_base"
fi

keys="time_factor time_ordering time_solve time_total cpu memory_peak_mb"
printf '%-16s %-5s %8s %9s %8s %8s %8s %8s\n' case cut factor ordering solve total cpu memMB
for c in $cases; do
  i=0
  while [ $i -lt "$reps" ]; do
    for cut in auto off; do
      /usr/bin/time -f '%U %S' -o "$work/cpu_$cut$i" "$prog" -q -o "$work/run_$cut$i" "$work/${c}_$cut.deck"
      awk '{printf "cpu %.3f\n", $1 + $2}' "$work/cpu_$cut$i" >> "$work/run_$cut$i/${c}_$cut.summary"
    done
    i=$((i + 1))
  done
  for cut in auto off; do
    for k in $keys; do
      for s in "$work"/run_$cut*/"${c}_$cut.summary"; do awk -v k="$k" '$1 == k {print $2}' "$s"; done | median
    done > "$work/med_$cut"
  done
  paste "$work/med_auto" "$work/med_off" | awk -v c="${c#cut_}" '
    {a[NR] = $1; o[NR] = $2}
    END {
      printf "%-16s %-5s %8.3f %9.3f %8.3f %8.3f %8.3f %8.0f\n", c, "auto", a[1], a[2], a[3], a[4], a[5], a[6]
      printf "%-16s %-5s %8.3f %9.3f %8.3f %8.3f %8.3f %8.0f\n", "", "off", o[1], o[2], o[3], o[4], o[5], o[6]
      printf "%-16s %-5s %8.3f %9.3f %8.3f %8.3f %8.3f %8.3f\n", "", "ratio", a[1] / o[1], a[2] / o[2], a[3] / o[3], a[4] / o[4], a[5] / o[5], a[6] / o[6]
    }'
  rm -rf "$work"/run_* "$work"/med_* "$work"/cpu_*
done
echo "(medians of $reps runs of each, in turn; seconds; cpu = user + sys; memMB = peak resident; ratio = auto / off)"
