#!/bin/sh
# studies/findings.sh TABLES TOPIC: the findings of the accuracy-cost report
# as Markdown prose, computed from the tables of studies/run-all, so that
# the words follow the numbers of the run.  TOPIC: front, lcp, master, slave, phases.
set -eu
t=$1
case $2 in

front)
  # the cheapest S runs by the mesh pair (upper nx over lower nx) and the solvers' CPU spread per configuration
  awk -F, 'NR == 1 { next } $1 == "S" { split($3, w, "_"); nl = substr(w[3], 2) + 0; nu = substr(w[4], 2) + 0
      q = nu / nl; cnt[q]++; n++ }
    END { printf "For S, the cheapest run at each target has an upper mesh"
      for (k in cnt) printf " %s times as fine as the lower one (%d of %d targets)", k, cnt[k], n
      printf "; which body is the slave and which solver was used come out mixed. "
      printf "The upper block, which takes the end tractions, carries about three times the error of the lower one (see \"Refining the master side\"), "
      printf "so the cheapest accuracy comes from the upper mesh about twice as fine as the lower, whichever is the slave.\n\n" }' "$t/cheapest.csv"
  awk -F, 'NR > 1 && $1 == "S" && $12 >= 0.1 { n++; s[n] = $11 + 0; if ($11 + 0 > mx) { mx = $11 + 0; mk = $2 } }
    END { for (i = 2; i <= n; i++) { x = s[i]; for (j = i - 1; j >= 1 && s[j] > x; j--) s[j + 1] = s[j]; s[j + 1] = x }
      printf "Within one mesh configuration of S (the %d that take at least 0.1 s) the three LCP solvers differ in CPU time by %.0f%% in the median (at most %.0f%%, %s), ", n, 100 * s[int((n + 1) / 2)], 100 * mx, mk
      printf "while they reach the same solution (see the agreement paragraph in \"Lemke against PGS\"): on the S and H sequences, with at most a few hundred contact nodes, the LCP is a small share of the run, "
      printf "so the choice of solver does not move the front; the mesh pair does.\n\n" }' "$t/agreement.csv"
  for fam in S H; do
    if [ $fam = S ]; then csv=$t/signorini.csv; else csv=$t/hertz.csv; fi
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $(c["status"]) == 0 && $(c["h1_rel"]) != "" { print $(c["cpu_time"]) + 0, $(c["h1_rel"]) + 0, $(c["time_lcp"]) / $(c["time_total"]) }' \
      "$csv" | sort -g | awk -v lab=$fam 'NR == 1 || $2 < best { best = $2; n++; if ($3 > sh) sh = $3 }
      END { printf "The %s front has %d runs; the LCP takes at most %.1f%% of the run time of any of them.\n\n", lab, n, 100 * sh }'
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
      printf "at the largest size measured the cheapest LCP solver is %s. `lcp=auto` switches from Lemke to PDAS above 100 contact nodes, ", best
      printf "later than the measured crossover, although what Lemke costs there is a small share of the run.\n"
    }
    function minr(a, m,    i, v) { v = a[1]; for (i = 1; i <= m; i++) if (a[i] < v) v = a[i]; return v }' "$t/crossover.csv"
  ;;

master)
  # per level: error and time factors from h2/h1 = 1 to 1/2 and 1/4, against refining both (level k+1, h2/h1 = 1);
  # the exponent log(error factor) / log(time factor) says how much error a doubling of cost buys
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { e[$1, $3] = $(c["h1_rel"]); tt[$1, $3] = $(c["cpu_time"]); if ($1 > kmax) kmax = $1 }
    END {
      print "| k | error x, master 1 -> 1/2 | time x | exponent | error x, master 1 -> 1/4 | time x | exponent | error x, both refined (k+1) | time x | exponent |"
      print "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
      for (k = 0; k <= kmax; k++) {
        if (e[k, 1] == "") continue
        printf "| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", k, q(e[k, 0.5], e[k, 1]), q(tt[k, 0.5], tt[k, 1]), x(e[k, 0.5], e[k, 1], tt[k, 0.5], tt[k, 1]),
          q(e[k, 0.25], e[k, 1]), q(tt[k, 0.25], tt[k, 1]), x(e[k, 0.25], e[k, 1], tt[k, 0.25], tt[k, 1]),
          q(e[k + 1, 1], e[k, 1]), q(tt[k + 1, 1], tt[k, 1]), x(e[k + 1, 1], e[k, 1], tt[k + 1, 1], tt[k, 1])
        if (k > 0 && e[k + 1, 1] != "" && e[k, 0.5] != "" && e[k, 0.25] != "") {
          a += lx(e[k, 0.5], e[k, 1], tt[k, 0.5], tt[k, 1]); b += lx(e[k, 0.25], e[k, 1], tt[k, 0.25], tt[k, 1]); na++
          d += lx(e[k + 1, 1], e[k, 1], tt[k + 1, 1], tt[k, 1]); nd++; klast = k }
      }
      printf "\n(exponent = log(error factor) / log(time factor): the more negative, the more error a unit of CPU time removes; "
      printf "k = 0 is left out of the means below, its runs last a few milliseconds; the means take the levels where all three moves were run.)\n\n"
      if (na > 0 && nd > 0) {
        a /= na; b /= na; d /= nd
        printf "Mean exponents for k = 1 ... %d: master 1 -> 1/2: **%.2f**; master 1 -> 1/4: **%.2f**; both meshes refined once: **%.2f**. ", klast, a, b, d
        if (a <= d + 0.05) printf "Refining the master to half the slave size buys error at least as cheaply as refining both meshes; "
        else printf "Refining the master to half the slave size buys error less cheaply than refining both meshes; "
        if (b > a) printf "going on to a quarter pays less (the slave'\''s error and the cost of the fine master take over): refinement of the master side stops paying off between h2/h1 = 1/2 and 1/4.\n"
        else printf "a quarter still pays as well.\n"
      }
    }
    function q(a, b) { return (a == "" || b == "" || b == 0) ? "" : sprintf("%.2f", a / b) }
    function x(e1, e0, t1, t0) { return (e1 == "" || e0 == "" || t1 <= 0 || t0 <= 0 || t1 == t0) ? "" : sprintf("%.2f", log(e1 / e0) / log(t1 / t0)) }
    function lx(e1, e0, t1, t0) { return (e1 == "" || e0 == "" || t1 <= 0 || t0 <= 0 || t1 == t0) ? 0 : log(e1 / e0) / log(t1 / t0) }' "$t/master.csv"
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
        printf "and refining it first pays, until its error has fallen to the slave'\''s level.\n"
      } else printf "\n"
    }'
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
      lg = 0; nn = 0; for (k = 1; k <= m; k++) if (p[k, "block"] != "" && p[k, "disk"] != "") { lg += log(p[k, "disk"] / p[k, "block"]); nn++ }
      g = (nn > 0) ? exp(lg / nn) : 1
      printf " (geometric mean from k = 1 on: %.2f). ", g
      if (g > 1.1) printf "The flat block side is the better slave for the pressure (the benchmark'\''s choice).\n"
      else if (g < 0.9) printf "The curved disk side is the better slave for the pressure.\n"
      else printf "Neither side is systematically better for the H1 error or the pressure once each is measured against its own model; the block side (the benchmark'\''s choice) keeps the contact traction vertical.\n" }' "$t/hertz.csv"
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
