#!/bin/sh
# bench/lcp.sh: the three LCP solvers against the number of contact nodes.
# Runs the benchmark table of tests/unit/test_lcp_newton.f90 with
# LCP_BENCH=1: manufactured contact-like LCPs (half the nodes in contact) on
# two Delassus kernels, the elastic half-plane (condition ~ n) and a 1D
# elastic foundation (condition ~ n^2), n = 100 ... 5000; PDAS (steps,
# time, and the time when every step refactors), Lemke (pivots, time) and
# PGS (sweeps, time, residual), CPU seconds.  Then Lemke's cost per pivot.
# About 7 minutes (Lemke at n = 5000 takes two of them per kernel).
# OPENBLAS_NUM_THREADS=1 in the environment for single-thread figures.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
mode=${MODE:-release}
prog=$top/build/$mode/tests/test_lcp_newton
make -s -C "$top" MODE="$mode" unit > /dev/null
out=$(mktemp "${TMPDIR:-/tmp}/c2d-lcp.XXXXXX")
trap 'rm -f "$out"' EXIT
LCP_BENCH=1 "$prog" > "$out"
grep '^#' "$out"
if grep -q '^FAIL' "$out"; then
  echo "bench/lcp.sh: the solvers failed their checks:" >&2
  grep '^FAIL' "$out" >&2
  exit 1
fi
echo
echo "Lemke: cost per pivot (time / pivots)"
awk '/^# +(half-plane|foundation) / && $5 == "|" {
       # kernel n contact | steps time refactor | pivots time | sweeps time residual
       for (i = 1; i <= NF; i++) if ($i == "|") bar[++nb] = i
       piv = $(bar[2] + 1); t = $(bar[2] + 2); nb = 0
       if (piv > 0) printf "  %-10s n = %5d: %6d pivots, %9.4f s, %8.3f ms per pivot\n", $2, $3, piv, t, 1000 * t / piv
     }' "$out"
