#!/bin/sh
# bench/contact.sh [REPEATS]: the cost of contact at scale.  Hertz (graded
# gmsh meshes, 600 slave nodes on the contact line) and Signorini (MESH rect,
# 501 and 801 slave nodes) at about 1e5 and 1e6 dofs.  Each case runs with
# CONTACT and, as the baseline, the same stiffness without CONTACT (default
# METIS ordering).  Prints medians over REPEATS runs (default 3) and the
# ratios of the targets:
#   overhead = (condense + lcp + recover) / factor              target <= 0.3
#   whole    = total(contact) / (factor + solve)(baseline)      target <= 1.3
#   memory   = peak resident / CHOLMOD factor memory             target <= 1.5
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/contact}
mkdir -p "$work"
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }

hertz_deck() { # name hc hf
  for part in block disk; do
    [ -f "$work/$1_$part.msh" ] || gmsh -2 -format msh41 -v 1 -setnumber hc "$2" -setnumber hf "$3" \
      "$top/bench/geo/hertz_${part}_graded.geo" -o "$work/$1_$part.msh"
  done
  cat > "$work/$1.deck" <<DECK
PLANE strain
BODY block
  MESH gmsh file=$1_block.msh
  MATERIAL isotropic E=200000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY disk
  MESH gmsh file=$1_disk.msh
  MATERIAL isotropic E=200000 nu=0.3
  FIX top ux=0 uy=-0.01
END
CONTACT slave=block:top master=disk:arc
DECK
}
signorini_deck() { # name nx1 ny1 nx2 ny2
  cat > "$work/$1.deck" <<DECK
PLANE strain
BODY lower
  MESH rect x0=0 y0=0 x1=2 y1=1 nx=$2 ny=$3
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY upper
  MESH rect x0=0 y0=1 x1=2 y1=2 nx=$4 ny=$5
  MATERIAL isotropic E=1000 nu=0.3
  FIX top ux=0 uy=0
  TRACTION right tx=0 ty=-20
  TRACTION left tx=0 ty=20
END
CONTACT slave=lower:top master=upper:bottom gap=zero
DECK
}
hertz_deck hertz_1e5 0.001 0.04
hertz_deck hertz_1e6 0.001 0.0095
signorini_deck signorini_1e5 500 50 400 60
signorini_deck signorini_1e6 800 400 600 300

printf '%-14s %8s %5s %6s %7s %8s %8s %7s %7s %8s %8s %7s | %8s %9s %8s\n' case dofs nodes active assemble factor \
  condense lcp recover total memMB fmemMB overhead whole memory
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
      'BEGIN {printf "%-14s %8d %5d %6d %7.3f %8.3f %8.3f %7.3f %7.3f %8.3f %8.0f %7.0f | %8.3f %9.3f %8.3f\n",
              c, d, n, act, a, f, co, l, r, t, m, fm, (co + l + r) / f, t / (bf + bs), m / fm}'
  rm -rf "$work"/run*
done
echo "(medians of $reps runs, seconds; baseline = the same bodies without CONTACT)"
