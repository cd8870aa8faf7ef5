#!/bin/sh
# bench/newton_lcp.sh [REPEATS]: each Newton iterate's contact problem in
# finite strain solved by Lemke's method on its LCP (SOLVER newton_lcp=lemke,
# the default) against one semismooth Newton step (newton_lcp=active_set:
# the last iterate's active set as equalities, updated from the step's
# multipliers and gaps), on the frictionless scenes the active-set iteration
# takes (doc/theory.md, "Finite strain: hyperelastic bodies"):
#   oring    tests/finite/oring/oring.deck, the plane-strain quarter O-ring
#            squeezed 30 % in 6 steps, hc 0.1 and 0.05;
#   block    tests/finite/block/block.deck, the neo-Hookean block squeezed
#            20 % by a rigid plate in 4 steps, K = 1000, 16 x 16 Q1;
#   axgroove tests/finite/axgroove/axgroove.deck frictionless (mu = 0): the
#            axisymmetric section held by its contacts alone, 20 % in 4 steps.
# For each: Newton iterations summed over the steps, halvings (sub-increments
# beyond one per step), the median of REPEATS runs (default 3) of cpu_total,
# and the largest relative difference of the RIGID's force between the two.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/common.sh"
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/newton_lcp}
mkdir -p "$work"
cp "$top"/tests/finite/oring/*.geo "$top"/tests/finite/axgroove/*.geo "$work/"

# make NAME SOURCE METHOD PARAMS...: NAME.deck, SOURCE with its PARAMETER
# defaults replaced and SOLVER newton_lcp=METHOD after its PLANE line
make() {
  name=$1 src=$2 method=$3
  shift 3
  sed -e "s/^PLANE \(.*\)/PLANE \1\nSOLVER newton_lcp=$method/" "$src" > "$work/$name.deck"
  for p in "$@"; do
    sed -i "s/^\(PARAMETER.*\) ${p%%=*}=[^ ]*/\1 $p/" "$work/$name.deck"
  done
}
force() { awk '$1 == "rigid" {print $7; exit}' "$work/out/$1.summary"; }
iters() { awk '$1 == "newton" {n += $3} END {print n}' "$work/out/$1.summary"; }
cuts() { grep -c 'the increment is halved' "$work/$1.log" || true; }

printf '| scene | method | newton iterations | halvings | cpu_total s (median of %s) | force |\n' "$reps"
printf '| --- | --- | --- | --- | --- | --- |\n'
for scene in "oring hc=0.1" "oring hc=0.05" block axgroove; do
  set -- $scene
  case $1 in
    oring) src=$top/tests/finite/oring/oring.deck; params="squeeze=0.3 steps=6 $2" ;;
    block) src=$top/tests/finite/block/block.deck; params="n=16" ;;
    axgroove) src=$top/tests/finite/axgroove/axgroove.deck; params="mu=0" ;;
  esac
  for method in lemke active_set; do
    name=$1_$method
    make "$name" "$src" "$method" $params
    "$prog" -o "$work/out" "$work/$name.deck" > "$work/$name.log" 2>&1 || echo "$name: exit $?" >&2
    run "$name"
    eval "f_$method=\$(force $name)"
    printf '| %s | %s | %s | %s | %s | %s |\n' "$scene" "$method" "$(iters "$name")" "$(cuts "$name")" \
      "$(printf %.3f "$(cat "$work/$name.cpu")")" "$(force "$name")"
  done
  awk -v a="$f_lemke" -v b="$f_active_set" 'BEGIN {d = (a - b) / a; if (d < 0) d = -d;
    printf "|   | relative difference of the forces | %.1e | | | |\n", d}'
done
