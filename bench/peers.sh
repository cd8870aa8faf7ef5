#!/bin/sh
# bench/peers.sh [REPEATS]: accuracy per second on the Hertz problem H,
# contact2d (P1, and quadratic when it takes contact on quadratic elements)
# against GetFEM 5.4 (Debian python3-getfem, nodal contact brick, P1 and P2)
# and CalculiX 2.20 (Debian calculix-ccx, surface-to-surface penalty, CPE3
# and CPE6), on even meshes and on meshes graded toward the zone's ends, and
# contact2d's ADAPT quantity=pressure (P1 and P2, from the even mesh at hc 0.08,
# one run per target: 3 %, 1 %, 0.3 %, 0.1 %; its time the whole adaptive
# run's, gmsh's re-meshings included).
# Error = pressure L2 error along the contact line and energy (H1) error near
# the zone, both against a reference of the same finite problem (a much finer
# contact2d solve on graded meshes, its own convergence printed); time =
# median user+sys CPU time of the solver process over up to REPEATS runs
# (default 3).  Prints the sweep, the reference's convergence and the CPU
# time at matched pressure error (1 %, 0.3 %, 0.1 %) and matched H1 error,
# with the speedup of contact2d over the faster peer, measured in this run.
# Goal (issue 25): quadratic contact2d at 0.1 % pressure error in under 1 s
# on one core, at least 10x faster than the faster peer at every accuracy
# both reach.  A peer that is not installed is skipped with a message.
# Outputs go to bench/out/peers/ (PEERS_OUT); PEERS_HC overrides the sweep,
# PEERS_SERIES the series (code:kind,...), PEERS_REF_HC the reference's finest
# size (levels 4, 2, 1 x it), PEERS_THREADS the threads per process (1),
# PEERS_TIMEOUT the wall-time limit of one run (s, default 300),
# PEERS_SERIES_STOP the CPU time (s, default 30) after which a series runs no
# finer point, PEERS_A the zone's half-width (default: located),
# PEERS_ADAPT_TARGETS the adaptive series' targets (comma-separated relative
# pressure errors), PEERS_ADAPT_MAX_DOFS their ADAPT max_dofs (500000),
# PEERS_ADAPT_HC the even mesh size they start from (0.08).
# PEERS_DOC=doc/accuracy-cost.md puts the tables (printed in markdown) into
# that page between its "bench/peers.sh" markers.
set -eu
export PYTHONDONTWRITEBYTECODE=1
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-3}
out=${PEERS_OUT:-$top/bench/out/peers}
py=/usr/bin/python3
[ -x "$prog" ] || make -C "$top" >/dev/null
[ -x "$py" ] || { echo "peers: $py not found" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "peers: gmsh not found" >&2; exit 1; }
series=${PEERS_SERIES:-contact2d:p1,contact2d:p1g,contact2d:p2,contact2d:p2g,contact2d:adapt1,contact2d:adapt2,getfem:p1,getfem:p1g,getfem:p2,getfem:p2g,ccx:p1,ccx:p1g,ccx:p2,ccx:p2g}
keep=
for s in $(echo "$series" | tr , ' '); do
  case $s in
    getfem:*) "$py" -c 'import getfem' >/dev/null 2>&1 || {
        echo "peers: $s skipped: python3-getfem is not installed (apt-get install python3-getfem)"; continue; } ;;
    ccx:*) command -v ccx >/dev/null 2>&1 || {
        echo "peers: $s skipped: ccx is not installed (apt-get install calculix-ccx)"; continue; } ;;
  esac
  keep=${keep:+$keep,}$s
done
"$py" -c 'import numpy, scipy' >/dev/null 2>&1 || { echo "peers: $py needs numpy and scipy (apt-get install python3-scipy)" >&2; exit 1; }
set -- --prog "$prog" --out "$out" --series "$keep" --reps "$reps" --threads "${PEERS_THREADS:-1}"
[ -z "${PEERS_HC:-}" ] || set -- "$@" --hc "$PEERS_HC"
[ -z "${PEERS_REF_HC:-}" ] || set -- "$@" --ref-hc "$PEERS_REF_HC"
[ -z "${PEERS_A:-}" ] || set -- "$@" --a "$PEERS_A"
[ -z "${PEERS_SERIES_STOP:-}" ] || set -- "$@" --series-stop "$PEERS_SERIES_STOP"
[ -z "${PEERS_TIMEOUT:-}" ] || set -- "$@" --timeout "$PEERS_TIMEOUT"
[ -z "${PEERS_ADAPT_TARGETS:-}" ] || set -- "$@" --adapt-targets "$PEERS_ADAPT_TARGETS"
[ -z "${PEERS_ADAPT_MAX_DOFS:-}" ] || set -- "$@" --adapt-max-dofs "$PEERS_ADAPT_MAX_DOFS"
[ -z "${PEERS_ADAPT_HC:-}" ] || set -- "$@" --adapt-hc "$PEERS_ADAPT_HC"
[ -z "${PEERS_DOC:-}" ] || set -- "$@" --doc "$(cd "$(dirname "$PEERS_DOC")" && pwd)/$(basename "$PEERS_DOC")"
exec "$py" "$top/bench/peers/driver.py" "$@"
