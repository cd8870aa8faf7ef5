#!/bin/sh
# bench/outputs.sh [OLD_PROGRAM]: the size of a load history's files, a
# 55-step loading-unloading cycle of a frictional model of about 25,000 nodes
# (a block pressed and sheared by a wider one, Coulomb mu = 0.3, OUTPUT
# steps=all).  Prints the bytes of the per-step VTK files, the binary size
# they hold uncompressed (the sum of the blocks' sizes their headers give),
# the per-step contact tables and the run's seconds (time_output, time_total,
# the run log's total), and the seconds of the same run with steps=last (the
# same steps solved, no file per step: what the files cost).  With OLD_PROGRAM (a build from before the XML files,
# which wrote a legacy ASCII NAME_NNNN.vtk per step) the same for it, and the
# ratio of the sizes.  Figures in doc/outputs.md ("Sizes of a load history").
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
old=${1:-}
work=${BENCH_OUT:-$top/bench/out/outputs}
mkdir -p "$work"
deck=$work/cycle.deck
cat > "$deck" <<'DECK'
! a load cycle: the top block pressed and sheared up to step 27, then back to 0.2 of it
PLANE strain
STEPS 55
CURVE cycle 0:0 27:1 55:0.2
BODY base
  MESH rect x0=0 y0=0 x1=2 y1=1 nx=160 ny=80
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY pad
  MESH rect x0=0.5 y0=1 x1=1.5 y1=1.5 nx=140 ny=80
  MATERIAL isotropic E=1000 nu=0.3
  FIX top ux=0.004 uy=-0.01 curve=cycle
END
CONTACT slave=pad:bottom master=base:top gap=zero mu=0.3
OUTPUT steps=all
DECK

# bytes of the files matching a pattern in a folder
bytes() { find "$1" -maxdepth 1 -name "$2" -printf '%s\n' | awk '{s += $1} END {print s + 0}'; }
count() { find "$1" -maxdepth 1 -name "$2" | wc -l; }
mb() { awk -v b="$1" 'BEGIN {printf "%.1f", b / 1e6}'; }

one() {  # one() LABEL PROGRAM [DECK]
  out=$work/$1
  rm -rf "$out"
  "$2" -o "$out" "${3:-$deck}" > "$work/$1.log"
  nodes=$(awk '$1 == "dofs" {print $2 / 2}' "$out/cycle.summary")
  vtk=$(bytes "$out" 'cycle_[0-9]*.vtk'); vtu=$(bytes "$out" 'cycle_[0-9]*.vtu')
  csv=$(bytes "$out" 'cycle_contact_[0-9]*.csv')
  files=$(( $(count "$out" 'cycle_[0-9]*.vt[ku]') ))
  printf '%-4s %6s nodes, %2s step files: legacy .vtk %8s MB, .vtu %8s MB' "$1" "$nodes" "$files" "$(mb "$vtk")" "$(mb "$vtu")"
  if [ "$vtu" -gt 0 ]; then
    raw=$(python3 - "$out" <<'PY'
import glob, re, struct, sys
total = 0
for path in glob.glob(sys.argv[1] + "/cycle_[0-9]*.vtu"):
    data = open(path, "rb").read()
    head = data[:data.index(b"<AppendedData")].decode()
    start = data.index(b"_", data.index(b"<AppendedData")) + 1
    total += len(head)
    for off in re.findall(r'offset="(\d+)"', head):
        at = start + int(off)
        if "vtkZLibDataCompressor" in head:
            nblock, block, last = struct.unpack_from("<3Q", data, at)
            total += 8 + (nblock - (last > 0)) * block + last
        else:
            total += 8 + struct.unpack_from("<Q", data, at)[0]
print(total)
PY
)
    printf ' (%s MB uncompressed)' "$(mb "$raw")"
  fi
  printf ', contact tables %s MB; time_output %s s, time_total %s s, run %s s\n' "$(mb "$csv")" \
    "$(awk '$1 == "time_output" {printf "%.2f", $2}' "$out/cycle.summary")" \
    "$(awk '$1 == "time_total" {printf "%.2f", $2}' "$out/cycle.summary")" \
    "$(awk '$1 == "total" {printf "%.2f", $2}' "$work/$1.log")"
  echo "$(( vtk + vtu ))" > "$work/$1.bytes"
}

one new "$prog"
mkdir -p "$work/lastdeck"
grep -v '^OUTPUT' "$deck" > "$work/lastdeck/cycle.deck"       # the same name: cycle.summary
one last "$prog" "$work/lastdeck/cycle.deck"
if [ -n "$old" ]; then
  one old "$old"
  awk -v a="$(cat "$work/old.bytes")" -v b="$(cat "$work/new.bytes")" \
    'BEGIN {printf "step files: old / new = %.1f\n", a / b}'
fi
