#!/bin/sh
# bench/adapt_graded.sh [REPEATS]: ADAPT quantity=pressure against the mesh an
# expert grades by hand toward the contact zone's ends (doc/accuracy-cost.md,
# "ADAPT against a hand-graded mesh").  Hertz (input/hertz.deck), P1 and P2
# (order=2), targets 1 %, 0.3 % and 0.1 % on the contact pressure.  Medians of
# REPEATS runs (default 3) of cpu_total, the run's CPU seconds with gmsh's
# included (--no-mesh-cache: every run meshes its .geo, as a first run does).
#  (a) The hand-graded mesh: bench/geo/hertz_{block,disk}_graded.geo, size hc
#      on both sides for |x| <= w = 0.1 (the zone's half-width a = 0.070 and a
#      margin), growing linearly to hf over the distance g = 1; hf = 0.2 for
#      P2, 0.05 for P1 (P1's pressure error is the bulk's as much as the
#      ends': at hf = 0.2 it stalls near 1.1 % whatever hc).  The family was
#      chosen from a calibration sweep (hc 0.0005 .. 0.01, w 0.1 / 0.3, g 0.3
#      / 0.5 / 1, hf 0.05 .. 0.2); for each target the script tries the hc of
#      its list, coarsest first, and keeps the first whose true error is at or
#      below the target (calibration: P2 hc = 0.005 0.895 %, 0.002 0.351 %,
#      0.001 0.167 %, 0.0007 0.087 %; P1 hc = 0.002 0.693 %, 0.001 0.352 %).
#  (b) ADAPT target=T quantity=pressure from the deck's .geo at hc = 0.05
#      (hf = 0.5): its meshes, dofs, estimate, true error and cpu_total.
# The true error: the relative L2 difference of the pressure against
# tests/estimate/hertz/reference_contact.csv (tests/lib/pressure_error.py),
# itself within about 0.1 % of the exact pressure (its PROVENANCE; the
# mesh-to-mesh differences put its own error near 0.03-0.05 %).  A mesh's
# error and the reference's are close to uncorrelated (they change sign with
# where the zone's end falls in an element), so a measured 0.1 % is the true
# one within about 0.01 % and the 1.5 x bound (0.15 %) is judged; errors below
# about 0.05 % are not resolved (a measured value there is an upper bound).
# ORDERS (default "2 1") and TARGETS (default "0.01 0.003 0.001") select.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/common.sh"
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
orders=${ORDERS:-2 1}
targets=${TARGETS:-0.01 0.003 0.001}
work=${BENCH_OUT:-$top/bench/out/adapt_graded}
ref=$top/tests/estimate/hertz/reference_contact.csv
mkdir -p "$work"
cp "$top/input/hertz_block.geo" "$top/input/hertz_disk.geo" \
   "$top/bench/geo/hertz_block_graded.geo" "$top/bench/geo/hertz_disk_graded.geo" "$work/"

true_error() { (cd "$top/tests/lib" && python3 pressure_error.py "$ref" "$work/out/$1_contact.csv"); }
estimate() { awk '$1 == "estimate" && $2 == "pressure" {print 100 * $4}' "$work/out/$1.summary"; }
# run NAME [N] (bench/common.sh): N runs (default REPEATS) of $work/NAME.deck; NAME.cpu holds the median cpu_total
graded() {  # graded NAME HC ORDER
  hf=0.2; [ "$3" = 2 ] || hf=0.05
  sed -e "s/hertz_block.geo hc=0.01 hf=0.5/hertz_block_graded.geo hc=$2 hf=$hf w=0.1 g=1 order=$3/" \
      -e "s/hertz_disk.geo hc=0.01 hf=0.5/hertz_disk_graded.geo hc=$2 hf=$hf w=0.1 g=1 order=$3/" \
      "$top/input/hertz.deck" > "$work/$1.deck"
}
adapt() {   # adapt NAME ORDER TARGET
  sed -e "s/hc=0.01 hf=0.5/hc=0.05 hf=0.5 order=$2/" "$top/input/hertz.deck" > "$work/$1.deck"
  echo "ADAPT target=$3 quantity=pressure" >> "$work/$1.deck"
}
# the graded sizes tried for each target, coarsest first
sizes() {   # sizes ORDER TARGET
  case "$1:$2" in
    2:0.01) echo 0.006 0.005 0.004 0.003 ;;
    2:0.003) echo 0.002 0.0017 0.0015 0.0012 0.001 ;;
    2:0.001) echo 0.0008 0.0007 0.0006 0.0005 0.0004 ;;
    1:0.01) echo 0.004 0.003 0.0025 0.002 ;;
    1:0.003) echo 0.001 0.0008 0.0007 0.0006 0.0005 ;;
    1:0.001) echo 0.0003 0.00025 0.0002 0.00015 ;;
  esac
}

printf '%-4s %7s | %8s %8s %8s %7s | %6s %8s %9s %8s %7s | %9s %11s\n' order target% \
  graded_hc dofs true% cpu_s meshes dofs estimate% true% cpu_s cpu_ratio true/target
for order in $orders; do
  for t in $targets; do
    # (a) the coarsest graded mesh at or below the target
    ghc=none; gname=
    for hc in $(sizes "$order" "$t"); do
      gname=graded_p${order}_$hc
      graded "$gname" "$hc" "$order"
      run "$gname" 1
      e=$(true_error "$gname")
      if awk -v e="$e" -v t="$t" 'BEGIN {exit !(e <= 100 * t)}'; then ghc=$hc; break; fi
    done
    [ "$reps" -le 1 ] || run "$gname"
    gs=$work/out/$gname.summary
    gtrue=$(true_error "$gname"); gcpu=$(cat "$work/$gname.cpu")
    # (b) ADAPT from the coarse start
    aname=adapt_p${order}_$t
    adapt "$aname" "$order" "$t"
    run "$aname"
    as=$work/out/$aname.summary
    atrue=$(true_error "$aname"); acpu=$(cat "$work/$aname.cpu")
    printf '%-4s %7s | %8s %8s %8.4f %7.3f | %6s %8s %9.4f %8.4f %7.3f | %9.3f %11.3f\n' "P$order" \
      "$(awk -v t="$t" 'BEGIN {print 100 * t}')" "$ghc" "$(key "$gs" dofs)" "$gtrue" "$gcpu" \
      "$(grep -c '^adapt ' "$as")" "$(key "$as" dofs)" "$(estimate "$aname")" "$atrue" "$acpu" \
      "$(awk -v a="$acpu" -v g="$gcpu" 'BEGIN {print a / g}')" \
      "$(awk -v e="$atrue" -v t="$t" 'BEGIN {print e / (100 * t)}')"
    [ "$ghc" != none ] || echo "  (no graded size of the list reached the target: the last one is shown)"
  done
done
