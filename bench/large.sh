#!/bin/sh
# bench/large.sh [HF]: the largest Hertz case, about 3.9e6 dofs (graded gmsh
# meshes, hc = 0.001, fine size HF, default 0.0047), in this machine's
# memory.  gmsh makes the two meshes once (about 4-5 minutes; they are kept
# in the output folder).  One contact run and one run of the same bodies
# without CONTACT, each under /usr/bin/time -v.  Prints the phases of the
# contact run, its peak memory against CHOLMOD's factor memory and against
# the machine's memory, and the ratios of bench/contact.sh:
#   overhead = (condense + lcp + recover) / factor              target <= 0.3
#   whole    = total(contact) / (factor + solve)(baseline)      target <= 1.3
#   memory   = peak resident / CHOLMOD factor memory             target <= 1.5
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
hf=${1:-0.0047}
work=${BENCH_OUT:-$top/bench/out/large}
mkdir -p "$work"
. "$top/bench/decks.sh"

name=hertz_hf$hf                     # the meshes of each HF kept apart
t0=$(date +%s)
hertz_deck "$work/$name.deck" "$name" 0.001 "$hf"      # gmsh, when the meshes are missing
t1=$(date +%s)
if [ $((t1 - t0)) -gt 1 ]; then echo "gmsh made the meshes (hc 0.001, hf $hf) in $((t1 - t0)) s"; fi
grep -v '^CONTACT' "$work/$name.deck" > "$work/${name}_base.deck"

for d in "$name" "${name}_base"; do
  /usr/bin/time -v -o "$work/$d.time" "$prog" -q -o "$work/out" "$work/$d.deck"
done

key() { awk -v k="$2" '$1 == k {print $2}' "$work/out/$1.summary"; }
rss() { awk -F': ' '/Maximum resident set size/ {print $2}' "$work/$1.time"; }
wall() { awk -F'): ' '/Elapsed \(wall clock\)/ {print $2}' "$work/$1.time"; }
echo "case $name: $(key $name dofs) dofs, $(key $name contact_nodes) contact nodes, nnz(L) $(key $name factor_nnz)"
for p in mesh assemble factor condense lcp recover output total; do
  printf '  %-9s %9.3f s\n' "$p" "$(key $name time_$p)"
done
printf '  (of which the ordering %.3f s)\n' "$(key $name time_ordering)"
mem=$(awk '/MemTotal/ {print $2}' /proc/meminfo)
awk -v m="$(key $name memory_peak_mb)" -v fm="$(key $name factor_memory_mb)" -v rss="$(rss $name)" -v mem="$mem" \
    -v w="$(wall $name)" -v bw="$(wall ${name}_base)" \
    -v co="$(key $name time_condense)" -v l="$(key $name time_lcp)" -v r="$(key $name time_recover)" \
    -v f="$(key $name time_factor)" -v t="$(key $name time_total)" \
    -v bf="$(key ${name}_base time_factor)" -v bs="$(key ${name}_base time_solve)" -v bt="$(key ${name}_base time_total)" \
    'BEGIN {
       printf "  peak memory %.0f MB (maximum resident %.0f MB, %.1f%% of the machine'"'"'s %.1f GiB)\n",
              m, rss / 1024, 100 * rss / mem, mem / 1048576
       printf "  wall clock %s (without CONTACT: %s, total %.3f s, factor + solve %.3f s)\n", w, bw, bt, bf + bs
       printf "overhead %.3f   whole %.3f   memory %.3f\n", (co + l + r) / f, t / (bf + bs), m / fm
     }'
rm -rf "$work/out"
