#!/bin/sh
# bench/peers.sh [REPEATS]: accuracy per second on the Hertz problem H against
# peers, side by side: contact2d, GetFEM 5.4 (Debian python3-getfem, run with
# /usr/bin/python3, nodal contact brick) and CalculiX 2.20 (Debian calculix-ccx,
# surface-to-surface penalty contact).  A sweep over the contact-zone mesh size
# hc, the same gmsh meshes for every code (meshed beforehand: meshing is not
# timed); error = relative L2 pressure error over |x| < a against Hertz with a,
# p0 from each code's own load P; time = whole-process wall time of the solver,
# median of up to REPEATS runs (default 5; runs longer than 30 s get fewer, see
# bench/peers/README.md); the user+sys CPU time is reported too (less disturbed
# than the wall time when the machine is shared).  Prints the sweep and the
# times at matched error (1%, 0.5%) with the speedup of contact2d over the
# faster peer.
# Goal (issue): contact2d at least 10x faster than the faster peer.
# A peer that is not installed is skipped with a message.  Outputs and inputs
# go to bench/out/peers/ (PEERS_OUT to change); PEERS_HC overrides the sweep
# (comma-separated hc values), PEERS_THREADS the threads per process (1).
set -eu
export PYTHONDONTWRITEBYTECODE=1
top=$(cd "$(dirname "$0")/.." && pwd)
prog=${CONTACT2D:-$top/bin/contact2d}
reps=${1:-5}
out=${PEERS_OUT:-$top/bench/out/peers}
py=/usr/bin/python3
[ -x "$prog" ] || make -C "$top" >/dev/null
[ -x "$py" ] || { echo "peers: $py not found" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "peers: gmsh not found" >&2; exit 1; }
codes=contact2d
if "$py" -c 'import getfem' >/dev/null 2>&1; then
  codes=$codes,getfem
else
  echo "peers: GetFEM skipped: python3-getfem is not installed (apt-get install python3-getfem)"
fi
if command -v ccx >/dev/null 2>&1; then
  codes=$codes,ccx
else
  echo "peers: CalculiX skipped: ccx is not installed (apt-get install calculix-ccx)"
fi
set -- --prog "$prog" --out "$out" --codes "$codes" --reps "$reps" --threads "${PEERS_THREADS:-1}"
[ -z "${PEERS_HC:-}" ] || set -- "$@" --hc "$PEERS_HC"
exec "$py" "$top/bench/peers/driver.py" "$@"
