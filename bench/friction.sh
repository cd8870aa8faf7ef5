#!/bin/sh
# bench/friction.sh [REPEATS] [NX ...]: the friction solvers' time against the
# number of friction unknowns.  A plate (40 x 10, plane strain, E = 1.3e5,
# nu = 0.2, quad4, NX x NX*40/128 elements) pressed on a rigid plane (its top
# moved down by 4e-4, step 1) and then sheared along it (its top moved by S,
# step 2), Coulomb friction mu = 1: Code_Aster's SSNV128 in spirit.  Each
# mesh (NX = 16 ... 1024 by default) runs with SOLVER lcp=lemke, pdas, pgs and
# auto at two shears: S = 8e-4 (a slip zone at the plate's ends) and S = 2e-3
# (nearly every node slips; PGS stalls from NX = 128).  Prints, per case, the
# median over REPEATS runs (default 3) of time_lcp (the two steps, seconds),
# the method's iterations (pivots, steps or sweeps) and the exit status (a
# failed run's time is the time it took to fail), then pdas / lemke and
# auto / best (the best of the three methods that solved the case).  A case
# whose first run takes more than SLOW seconds (default 30) runs once; Lemke
# does not run above LEMKE_MAX unknowns of its LCP (default 2100: at 4100 it
# takes some ten minutes a run).  One thread (-j 1).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
[ $# -gt 0 ] && shift
sizes=${*:-16 32 64 128 256 512 1024}
slow=${SLOW:-30}
lemke_max=${LEMKE_MAX:-2100}
work=${BENCH_OUT:-$top/bench/out/friction}
mkdir -p "$work"
. "$top/bench/common.sh"

for method in lemke pdas pgs auto; do
  cat > "$work/plate_$method.deck" <<DECK
PARAMETER nx=128 ny=40 s=2e-3
PLANE strain
STEPS 2
BODY plate
  MESH rect x0=0 y0=0 x1=40 y1=10 nx=\${nx} ny=\${ny} elem=quad4
  MATERIAL isotropic E=1.3e5 nu=0.2
  FIX top uy=-4e-4 ramp=0:1
  FIX top ux=\${s} ramp=1:2
END
RIGID plane
  SHAPE line x0=-10 y0=0 x1=50 y1=0
END
CONTACT slave=plate:bottom master=plane mu=1
SOLVER lcp=$method
DECK
done

# key VALUE of a summary
key() { awk -v k="$1" '$1 == k { print $2; exit }' "$2"; }

printf '%-6s %5s %5s %6s %6s |' shear nx ny n+nt n+3nt
for method in lemke pdas pgs auto; do printf ' %-28s |' "$method: s iterations exit"; done
printf ' %9s %9s\n' pdas/lemke auto/best
for s in 8e-4 2e-3; do
  for nx in $sizes; do
    ny=$((nx * 40 / 128))
    [ "$ny" -lt 4 ] && ny=4
    nrow=$((nx + 1))
    printf '%-6s %5d %5d %6d %6d |' "$s" "$nx" "$ny" $((2 * nrow)) $((4 * nrow))
    best=
    for method in lemke pdas pgs auto; do
      r=$reps
      if [ "$method" = lemke ] && [ $((4 * nrow)) -gt "$lemke_max" ]; then
        printf ' %-28s |' "(not run)"
        eval "t_$method="
        continue
      fi
      times=
      i=0
      while [ "$i" -lt "$r" ]; do
        i=$((i + 1))
        out="$work/${method}_${s}_$nx"
        rm -rf "$out"
        status=0
        /usr/bin/time -f '%e' -o "$out.time" "$prog" -q -j 1 -o "$out" -D nx="$nx" -D ny="$ny" -D s="$s" \
          "$work/plate_$method.deck" 2> "$out.err" || status=$?
        if [ "$status" -eq 0 ]; then
          t=$(key time_lcp "$out/plate_$method.summary")
          it=$(key lcp_iterations "$out/plate_$method.summary")
        else
          t=$(tail -n 1 "$out.time")      # a failed run writes no summary: the whole run's time
          it=-
        fi
        times="$times$t
"
        if [ "$i" -eq 1 ] && awk -v a="$(tail -n 1 "$out.time")" -v b="$slow" 'BEGIN { exit !(a > b) }'; then r=1; fi
      done
      tm=$(printf '%s' "$times" | median)
      eval "t_$method=$tm"
      printf ' %10.4f %10s %5s%s |' "$tm" "$it" "$status" "$([ "$r" -lt "$reps" ] && echo '*' || echo ' ')"
      if [ "$method" != auto ] && [ "$status" -eq 0 ]; then
        if [ -z "$best" ] || awk -v a="$tm" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$tm; fi
      fi
    done
    ratio() { if [ -n "$1" ] && [ -n "$2" ]; then awk -v a="$1" -v b="$2" 'BEGIN { printf "%9.3f", a / b }'; else printf '%9s' -; fi; }
    printf ' %s %s\n' "$(ratio "$t_pdas" "$t_lemke")" "$(ratio "$t_auto" "$best")"
  done
done
echo "(* one run, not a median; exit 1: the method failed, its time is the failed run's)"
