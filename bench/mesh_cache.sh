#!/bin/sh
# bench/mesh_cache.sh [N] [REPEATS]: what the mesh cache saves a sweep whose
# cases share one geometry.  N cases (default 8) of the Hertz problem H (both
# bodies .geo files meshed by gmsh at hc = 0.01, 10,724 dofs), one prescribed
# displacement per case, run by `contact2d --cases` one after the other into
# one folder, (a) with --no-mesh-cache (every case runs gmsh, as before the
# cache) and (b) with the cache (the first case runs gmsh, the others read its
# meshes).  Each sweep starts from an empty folder; timed REPEATS times
# (default 5), medians printed: the sweep's wall time, and the cases' median
# time_mesh and time_total from their summaries.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
n=${1:-8}
reps=${2:-5}
work=${BENCH_OUT:-$top/bench/out/mesh_cache}
rm -rf "$work"
mkdir -p "$work"
. "$top/bench/common.sh"
cat > "$work/hertz.deck" <<DECK
PARAMETER d=0.01
PLANE strain
BODY block
  MESH gmsh file=$top/input/hertz_block.geo hc=0.01 hf=0.5
  MATERIAL isotropic E=200000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY disk
  MESH gmsh file=$top/input/hertz_disk.geo hc=0.01 hf=0.5
  MATERIAL isotropic E=200000 nu=0.3
  FIX top ux=0 uy=\${-d}
END
CONTACT slave=block:top master=disk:arc
SOLVER lcp=lemke
DECK
{ echo d; i=1; while [ $i -le "$n" ]; do echo "0.00$i"; i=$((i + 1)); done; } > "$work/cases.csv"
now() { date +%s.%N; }
# key VALUE of every case's summary, one per line
keys() { for f in "$work"/sw/case_*/hertz.summary; do awk -v k="$1" '$1 == k {print $2}' "$f"; done; }
echo "bench/mesh_cache.sh: $n cases of Hertz H, $(nproc) cores, OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}, median of $reps"
printf '%-14s %10s %16s %16s\n' how 'sweep (s)' 'case mesh (s)' 'case total (s)'
for how in no_cache cache; do
  r=1
  : > "$work/$how.sweep"; : > "$work/$how.mesh"; : > "$work/$how.total"
  while [ $r -le "$reps" ]; do
    rm -rf "$work/sw"
    opt=""
    [ $how = no_cache ] && opt=--no-mesh-cache
    t0=$(now)
    "$prog" -q $opt --cases "$work/cases.csv" -o "$work/sw" "$work/hertz.deck"
    t1=$(now)
    echo "$t0 $t1" | awk '{print $2 - $1}' >> "$work/$how.sweep"
    keys time_mesh >> "$work/$how.mesh"
    keys time_total >> "$work/$how.total"
    r=$((r + 1))
  done
  printf '%-14s %10.3f %16.3f %16.3f\n' "$how" "$(median < "$work/$how.sweep")" "$(median < "$work/$how.mesh")" \
    "$(median < "$work/$how.total")"
done
