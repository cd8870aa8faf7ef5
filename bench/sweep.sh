#!/bin/sh
# bench/sweep.sh [N] [REPEATS]: the overhead of scripts/sweep.  N small cases
# (default 16: the two-block press of tests/params, 2 x 24^2 + 12^2 cells, one
# displacement per case) run (a) as N lone runs `contact2d -D d=...` in a shell
# loop, one after the other, and (b) through scripts/sweep on GNU parallel with
# -j 1 and with -j (the cores); each timed REPEATS times (default 3), the
# median printed.  The sweep's time includes its table check, its resume scan
# and the collection of cases.csv.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
n=${1:-16}
reps=${2:-3}
work=${BENCH_OUT:-$top/bench/out/sweep}
rm -rf "$work"
mkdir -p "$work"
. "$top/bench/common.sh"
cores=$(nproc)
cat > "$work/press.deck" <<'DECK'
PARAMETER d=0.01 n=12
BODY lower
  MESH rect x0=0 y0=0 x1=1 y1=1 nx=${2*n} ny=${2*n}
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom uy=0
  FIX left ux=0
END
BODY upper
  MESH rect x0=0 y0=1 x1=1 y1=2 nx=${n} ny=${n}
  MATERIAL isotropic E=1000 nu=0.3
  FIX left ux=0
  FIX top uy=${-d}
END
CONTACT slave=lower:top master=upper:bottom gap=zero
DECK
{ echo d; i=1; while [ $i -le "$n" ]; do echo "0.00$i"; i=$((i + 1)); done; } > "$work/cases.csv"
now() { date +%s.%N; }
loop() {
  i=1
  while [ $i -le "$n" ]; do
    "$prog" -q -D "d=0.00$i" -o "$work/loop/case_$i" "$work/press.deck"
    i=$((i + 1))
  done
}
echo "bench/sweep.sh: $n cases, $cores cores, median of $reps"
for how in loop sweep_j1 sweep_jall; do
  r=1
  while [ $r -le "$reps" ]; do
    rm -rf "$work/loop" "$work/sw"
    t0=$(now)
    case $how in
      loop) loop ;;
      sweep_j1) "$top/scripts/sweep" -j 1 -o "$work/sw" "$work/press.deck" "$work/cases.csv" > /dev/null ;;
      sweep_jall) "$top/scripts/sweep" -j "$cores" -o "$work/sw" "$work/press.deck" "$work/cases.csv" > /dev/null ;;
    esac
    t1=$(now)
    echo "$t0 $t1" | awk '{print $2 - $1}'
    r=$((r + 1))
  done > "$work/$how.times"
  printf '%-12s %8.3f s\n' "$how" "$(median < "$work/$how.times")"
done
