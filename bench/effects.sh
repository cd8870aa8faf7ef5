#!/bin/sh
# bench/effects.sh [REPEATS]: what each declared effect costs, and that an
# undeclared one costs nothing.  One Hertz scene of about 1e5 dofs (graded gmsh
# meshes, 600 slave nodes) in variants that differ by one effect:
#   no_contact      the two bodies, no CONTACT
#   frictionless    CONTACT
#   mu_zero         CONTACT mu=0 STEPS 10 (friction declared, zero bound)
#   coulomb_1       CONTACT mu=0.3, one step
#   coulomb_10      CONTACT mu=0.3, STEPS 10: pressed (steps 1-4), then a
#                   sideways push of the disk's top (steps 5-10)
#   gravity_zero    frictionless + DENSITY and GRAVITY gy=0
# Prints the median over REPEATS runs (default 3) of every phase.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
work=${BENCH_OUT:-$top/bench/out/effects}
mkdir -p "$work"
. "$top/bench/common.sh"
for part in block disk; do
  [ -f "$work/$part.msh" ] || gmsh -2 -format msh41 -v 1 -setnumber hc 0.001 -setnumber hf 0.04 \
    "$top/bench/geo/hertz_${part}_graded.geo" -o "$work/$part.msh"
done
deck() { # name contact-line extra-block-lines global-lines disk-fix-lines
  cat > "$work/$1.deck" <<DECK
PLANE strain
BODY block
  MESH gmsh file=block.msh
  MATERIAL isotropic E=200000 nu=0.3
  FIX bottom ux=0 uy=0
$3
END
BODY disk
  MESH gmsh file=disk.msh
  MATERIAL isotropic E=200000 nu=0.3
$5
END
$2
$4
DECK
}
one='  FIX top ux=0 uy=-0.01'
ten='  FIX top uy=-0.01 ramp=0:4
  FIX top ux=0.0035 ramp=4:10'
c='CONTACT slave=block:top master=disk:arc'
deck no_contact   ""           ""                     ""          "$one"
deck frictionless "$c"         ""                     ""          "$one"
deck mu_zero      "$c mu=0"    ""                     "STEPS 10"  "$ten"
deck coulomb_1    "$c mu=0.3"  ""                     ""          "$one"
deck coulomb_10   "$c mu=0.3"  ""                     "STEPS 10"  "$ten"
deck gravity_zero "$c"         "  DENSITY rho=7.8e-9" "GRAVITY gx=0 gy=0" "$one"
printf '%-13s %7s %5s %7s %8s %7s %8s %7s %7s %7s %7s %7s  %s\n' case dofs rows mesh assemble factor condense lcp recover output total iters effects
for c in no_contact frictionless mu_zero coulomb_1 coulomb_10 gravity_zero; do
  for i in $(seq "$reps"); do
    (cd "$work" && "$prog" -q -o "$work/$c.$i" "$c.deck")
  done
  get() { for i in $(seq "$reps"); do awk -v k="$1" '$1 == k {print $2}' "$work/$c.$i/$c.summary"; done | median; }
  s="$work/$c.1/$c.summary"
  printf '%-13s %7s %5s %7.3f %8.3f %7.3f %8.3f %7.3f %8.3f %7.3f %7.3f %7s  %s\n' "$c" \
    "$(awk '$1=="dofs"{print $2}' "$s")" "$(awk '$1=="contact_nodes"{print $2}' "$s")" \
    "$(get time_mesh)" "$(get time_assemble)" "$(get time_factor)" "$(get time_condense)" "$(get time_lcp)" \
    "$(get time_recover)" "$(get time_output)" "$(get time_total)" "$(awk '$1=="lcp_iterations"{print $2}' "$s")" \
    "$(sed -n 's/^effects //p' "$s")"
done
