#!/bin/sh
# studies/verdict.sh TABLES: the paragraph of doc/convergence.md that sets the
# fitted H1 rates against the paper's bound (3/4), computed from rates.csv.
set -eu
awk -F, '($2 == "h1_rel" || $2 == "h1w_rel") && $1 !~ /levels/ { n++; if (n == 1 || $4 < lo) { lo = $4; los = $1 } if (n == 1 || $4 > hi) { hi = $4; his = $1 }
    if ($4 < 0.75) bad = bad (bad == "" ? "" : "; ") $1 sprintf(" (%.2f)", $4) }
  END {
    printf "Over the %d fitted H1 series (whole domain and, for S, the interior window) the rates lie between %.2f (%s) and %.2f (%s). ", n, lo, los, hi, his
    if (bad == "")
      printf "None is below the paper'\''s 3/4: the mortar discretisation converges at least as fast as the bound O(h1^{3/4} + h2), and close to O(h) as expected in practice.\n"
    else
      printf "**Below 3/4: %s.** [benchmarks.md](benchmarks.md#what-a-build-must-show) counts a rate below the bound as a bug until explained; see the tables above.\n", bad
  }' "$1/rates.csv"
