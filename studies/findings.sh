#!/bin/sh
# studies/findings.sh TABLES TOPIC: the findings of the accuracy-cost report
# as Markdown prose, computed from the tables of studies/run-all, so that
# the words follow the numbers of the run.  TOPIC: front, lcp, master, slave, phases.
set -eu
t=$1
case $2 in

front)
  # the front of S and H: the runs on it, their ratios, solvers and LCP shares
  for fam in S H; do
    if [ $fam = S ]; then csv=$t/signorini.csv; lab="S"; else csv=$t/hertz.csv; lab="H"; fi
    awk -F, -v lab=$lab 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $(c["status"]) == 0 && $(c["h1_rel"]) != "" {
        print $(c["cpu_time"]) + 0, $(c["h1_rel"]) + 0, $(c["ratio"]), $(c["lcp"]), $(c["slave"]), $(c["time_lcp"]) / $(c["time_total"]), $(c["name"]) }' \
      "$csv" | sort -g | awk -v lab=$lab 'NR == 1 || $2 < best { best = $2; n++; r[$3]++; l[$4]++; s[$5]++; if ($6 > sh) sh = $6 }
      END {
        printf "On the %s front (%d runs): h2/h1 =", lab, n
        for (k in r) printf " %s (%d)", k, r[k]
        printf "; solver"; for (k in l) printf " %s (%d)", k, l[k]
        printf "; slave"; for (k in s) printf " %s (%d)", k, s[k]
        printf ". The LCP takes at most %.1f%% of the time of any run on it.\n\n", 100 * sh }'
  done
  ;;

lcp)
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { m++; n[m] = $1; r[m] = $(c["lcp_ratio"]); x[m] = $(c["extra"]); sl[m] = $(c["share_lemke"]); sp[m] = $(c["share_pgs"])
      pd[m] = $(c["pdas_ratio"]); it[m] = $(c["it_pdas"]) }
    END {
      lo = ""; for (i = 1; i <= m; i++) if (r[i] < 1) lo = lo (lo == "" ? "" : ", ") n[i]
      printf "Lemke is the cheaper LCP solver at n = %s contact nodes", (lo == "" ? "none of the sizes" : lo)
      printf " (ratios Lemke/PGS down to %.2f); ", minr(r, m)
      printf "its LCP time grows faster than PGS'\''s and is %.0f times PGS'\''s at n = %d. ", r[m], n[m]
      f = ""; for (i = 1; i <= m; i++) if (x[i] > 0.1) { f = n[i]; break }
      if (f != "") printf "Counted in the whole run, Lemke first costs more than 10%% extra at n = %d", f
      else printf "Counted in the whole run, Lemke never costs more than 10%% extra in this range"
      printf " (at n = %d: %.0f%% extra; the LCP is %.1f%% of Lemke'\''s run and %.1f%% of PGS'\''s). ", n[m], 100 * x[m], 100 * sl[m], 100 * sp[m]
      if (pd[m] != "") {
        printf "PDAS needs %s Newton steps at n = %d; its LCP time is %.2f times PGS'\''s at n = %d and %.2f times at n = %d. ", it[m], n[m], pd[1], n[1], pd[m], n[m]
      }
      best = "PGS"; if (pd[m] != "" && pd[m] < 1) best = "PDAS"; if (r[m] < 1 && (pd[m] == "" || r[m] < pd[m])) best = "Lemke"
      printf "Below a hundred or so contact nodes every LCP time is a fraction of a millisecond and the choice does not matter; "
      printf "at the largest size measured the cheapest LCP solver is %s. `lcp=auto` switches from Lemke to PGS at 1000 contact nodes, ", best
      printf "later than the measured crossover, although what Lemke costs there is a small share of the run.\n"
    }
    function minr(a, m,    i, v) { v = a[1]; for (i = 1; i <= m; i++) if (a[i] < v) v = a[i]; return v }' "$t/crossover.csv"
  ;;

master)
  # per level: error and time factors from h2/h1 = 1 to 1/2 and 1/4, against refining both (level k+1, h2/h1 = 1)
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { e[$1, $3] = $(c["h1_rel"]); tt[$1, $3] = $(c["cpu_time"]); if ($1 > kmax) kmax = $1 }
    END {
      print "| k | error x, master 1 -> 1/2 | time x | error x, master 1 -> 1/4 | time x | error x, both refined (k+1, h2/h1 = 1) | time x |"
      print "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
      for (k = 0; k <= kmax; k++) {
        if (e[k, 1] == "") continue
        printf "| %d | %s | %s | %s | %s | %s | %s |\n", k, q(e[k, 0.5], e[k, 1]), q(tt[k, 0.5], tt[k, 1]),
          q(e[k, 0.25], e[k, 1]), q(tt[k, 0.25], tt[k, 1]), q(e[k + 1, 1], e[k, 1]), q(tt[k + 1, 1], tt[k, 1])
      }
    }
    function q(a, b) { return (a == "" || b == "" || b == 0) ? "" : sprintf("%.2f", a / b) }' "$t/master.csv"
  echo
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $(c["status"]) == 0 && $(c["ratio"]) == 1 && $(c["slave"]) == "lower" && $(c["lcp"]) == "pgs" {
      printf "%s %s %s\n", $(c["level"]), $(c["h1_body1"]), $(c["h1_body2"]) }' "$t/signorini.csv" | sort -n |
    awk '{ r[$1] = $3 / $2; k[++m] = $1; if (m == 1 || r[$1] < rmin) rmin = r[$1] } END {
      printf "At h2/h1 = 1 the master (upper) body'\''s broken H1 error is"
      for (i = 1; i <= m; i++) printf "%s %.1f", (i > 1 ? "," : ""), r[k[i]]
      printf " times the slave'\''s at k = %d ... %d. ", k[1], k[m]
      if (rmin > 1) {
        printf "The upper block takes the end tractions and its stresses vary most, so it carries most of the error, "
        printf "and refining the master first pays: it removes the larger error at a cost that grows with the master only. "
        printf "It stops paying off once the master'\''s error has fallen to the slave'\''s level. "
      }
      printf "The table gives the factors by which h2/h1 = 1/2 and 1/4 change the error and the time, against refining both meshes once (the next level).\n" }'
  ;;

slave)
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $(c["err_lower"]) != "" && $(c["err_upper"]) != "" {
      d = $(c["err_upper"]) / $(c["err_lower"]) - 1; if (d < 0) d = -d; if (d > dmax) dmax = d
      fine = ($(c["nl"]) > $(c["nu"])) ? "lower" : "upper"; coarse = (fine == "lower") ? "upper" : "lower"
      pf += log($(c["p_l2_" fine]) / $(c["p_l2_" coarse])); ff += log($(c["F_max_" fine]) / $(c["F_max_" coarse])); np++ }
    END {
      printf "The H1 error hardly depends on which body is the slave: the two choices differ by at most %.1f%% over the %d mesh pairs. ", 100 * dmax, np
      printf "The pressure does: with the finer mesh as the slave the nodal L2 pressure error is on average %.1f times ", exp(pf / np)
      printf "that with the coarser one as the slave (the multiplier lives on the finer slave trace and oscillates where the master cannot resolve it), "
      printf "while the resultant distribution error is %.2f times as large. ", exp(ff / np)
      printf "The finer slave also has more contact nodes, hence a larger LCP. "
      printf "For the cheapest smooth pressure take the coarser side as the slave; the paper'\''s bound O(h1^{3/4} + h2), weaker in h1, "
      printf "would suggest the finer side, but at these sizes the bound'\''s asymmetry is not visible in the H1 error.\n" }' "$t/slave.csv"
  echo
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $(c["status"]) == 0 && $(c["ratio"]) == 1 && $(c["lcp"]) == "lemke" {
      k = $(c["level"]); e[k, $(c["slave"])] = $(c["h1_rel"]); p[k, $(c["slave"])] = $(c["p_l2"]); if (k > m) m = k }
    END {
      printf "Hertz: the H1 error with slave = disk over slave = block, level by level:"
      for (k = 0; k <= m; k++) if (e[k, "block"] != "" && e[k, "disk"] != "") printf " %.3f", e[k, "disk"] / e[k, "block"]
      printf "; the L2 pressure error (against the reference):"
      for (k = 0; k <= m; k++) if (p[k, "block"] != "" && p[k, "disk"] != "") printf " %.2f", p[k, "disk"] / p[k, "block"]
      printf ". The flat block side is the better slave for the pressure (the benchmark'\''s choice).\n" }' "$t/hertz.csv"
  ;;

agreement)
  awk -F, 'NR > 1 { n++; s += $3; if ($4 != $5) { d++; dl = dl (dl == "" ? "" : "; ") $2 " (" $4 " to " $5 " active nodes)" }
      if ($6 > e) { e = $6; ek = $2 } if ($7 > en) en = $7; if ($8 > r) { r = $8; rk = $2 } if ($9 > cp) cp = $9; if ($10 < g) g = $10 }
    END {
      printf "**The LCP solvers against each other** (%d mesh configurations of S and H, %d runs): ", n, s
      if (d == 0) printf "the same number of active nodes in every configuration; "
      else printf "the number of active nodes differs in %d configuration(s): %s; ", d, dl
      if (e > 0) printf "the relative H1 errors differ by at most %.1e (relative, %s) and the energies by at most %.1e; ", e, ek, en
      else printf "the H1 errors agree to all printed digits and the energies to %.1e (relative); ", en
      printf "the largest LCP residual reported is %.1e (%s), the largest complementarity %.1e, the most negative final gap %.1e.\n", r, rk, cp, g }' "$t/agreement.csv"
  ;;

phases)
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[i] = $i; next }
    { s = $1; if (!(s in first)) { first[s] = $0; order[++m] = s } last[s] = $0 }
    END {
      for (j = 1; j <= m; j++) { s = order[j]
        split(first[s], a, ","); split(last[s], b, ",")
        printf "* %s: at %d dofs the largest phase is %s (%.0f%%), at %d dofs %s (%.0f%%); factor %.0f%% -> %.0f%%, output %.0f%% -> %.0f%%, lcp %.1f%% -> %.1f%%.\n",
          s, a[2], big(a), 100 * bigv(a), b[2], big(b), 100 * bigv(b), 100 * a[6], 100 * b[6], 100 * a[10], 100 * b[10], 100 * a[8], 100 * b[8]
      }
    }
    function big(a,    i, k) { k = 4; for (i = 4; i <= 11; i++) if (a[i] > a[k]) k = i; return h[k] }
    function bigv(a,    i, k) { k = 4; for (i = 4; i <= 11; i++) if (a[i] > a[k]) k = i; return a[k] }' "$t/phases.csv"
  ;;
esac
