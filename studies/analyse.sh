#!/bin/sh
# studies/analyse.sh OUT: the derived findings of the studies, as small CSV
# tables in OUT/tables (read by studies/mkdoc.sh):
#   crossover.csv  Lemke against PGS on the LCP sweep (fastest of the repeats):
#                  per n the LCP times, the run times without the mesh phase,
#                  Lemke's extra LCP time as a share of PGS's total time, and in
#                  crossover_n.csv the n* where Lemke's LCP time passes PGS's for
#                  good (log-linear interpolation of the ratio)
#   cheapest.csv   per family and accuracy target, the cheapest run reaching it
#   master.csv     S at fixed slave mesh: error and time per h2/h1
#   slave.csv      S mesh pairs solved with either body as the slave
#   phases.csv     shares of the phases in the total time along the sequences
#   agreement.csv  per mesh configuration of S and H, the LCP solvers against
#                  each other: active nodes, H1 error, energy, worst residual
set -eu
out=$1
t=$out/tables

# ---------------------------------------------------------------- crossover
# "run" time = total - mesh: the mesh phase (gmsh) does not depend on the solver and is noisy
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
  { n = $(c["contact_nodes"]); k[n] = 1
    T[n, $2] = $(c["time_lcp"]); TT[n, $2] = $(c["time_total"]) - $(c["time_mesh"]); IT[n, $2] = $(c["lcp_iterations"])
    SH[n, $2] = $(c["time_lcp"]) / $(c["time_total"]); T0[n, $2] = $(c["time_mesh"]) }
  END {
    m = 0; for (n in k) ns[++m] = n + 0
    for (i = 2; i <= m; i++) { x = ns[i]; for (j = i - 1; j >= 1 && ns[j] > x; j--) ns[j + 1] = ns[j]; ns[j + 1] = x }
    print "contact_nodes,time_lcp_lemke,time_lcp_pgs,time_lcp_pdas,lcp_ratio,pdas_ratio,time_run_lemke,time_run_pgs,run_ratio,it_lemke,it_pgs,it_pdas,share_lemke,share_pgs,share_pdas,extra"
    for (i = 1; i <= m; i++) { n = ns[i]
      if (T[n, "lemke"] == "" || T[n, "pgs"] == "") continue
      printf "%d,%s,%s,%s,%.4g,%s,%.6g,%.6g,%.4g,%s,%s,%s,%.4f,%.4f,%s,%.4f\n", n, T[n, "lemke"], T[n, "pgs"], T[n, "pdas"],
        T[n, "lemke"] / T[n, "pgs"], (T[n, "pdas"] == "" ? "" : sprintf("%.4g", T[n, "pdas"] / T[n, "pgs"])),
        TT[n, "lemke"], TT[n, "pgs"], TT[n, "lemke"] / TT[n, "pgs"], IT[n, "lemke"], IT[n, "pgs"], IT[n, "pdas"],
        SH[n, "lemke"], SH[n, "pgs"], (SH[n, "pdas"] == "" ? "" : sprintf("%.4f", SH[n, "pdas"])),
        (T[n, "lemke"] - T[n, "pgs"]) / (TT[n, "pgs"] + T0[n, "pgs"]) }
  }' "$t/lcp_best.csv" > "$t/crossover.csv"
# n*: where log(Lemke / PGS) turns positive for good (log-linear interpolation);
# "<N": Lemke is dearer from the first size on; blank: Lemke is not dearer at the largest size
for q in lcp; do
  awk -F, -v q=$q 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { m++; n[m] = $1; r[m] = log($(c[q "_ratio"])) }
    END { x = ""
          if (m > 0 && r[m] > 0) {
            x = "<" n[1]
            for (i = m; i > 1; i--) if (r[i - 1] <= 0) {
              x = exp(log(n[i - 1]) + (log(n[i]) - log(n[i - 1])) * (0 - r[i - 1]) / (r[i] - r[i - 1])); break } }
          print q "," x }' "$t/crossover.csv"
done > "$t/crossover_n.csv"

# ---------------------------------------------------------------- cheapest run per accuracy target
{
  echo "family,target,name,slave,ratio,lcp,h1,h2,dofs,contact_nodes,h1_rel,cpu_time,runs_reaching"
  for fam in S H; do
    if [ $fam = S ]; then csv=$t/signorini.csv; targets="0.2 0.1 0.05 0.03 0.02"; else csv=$t/hertz.csv; targets="0.1 0.05 0.03 0.02 0.015"; fi
    for tg in $targets; do
      awk -F, -v tg=$tg -v fam=$fam 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
        $(c["status"]) == 0 && $(c["h1_rel"]) != "" && $(c["h1_rel"]) <= tg { cnt++
          if (best == "" || $(c["cpu_time"]) < bt) { bt = $(c["cpu_time"]); best = $0 } }
        END { if (best != "") { split(best, f, ",")
          printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%d\n", fam, tg, f[c["name"]], f[c["slave"]], f[c["ratio"]],
            f[c["lcp"]], f[c["h1"]], f[c["h2"]], f[c["dofs"]], f[c["contact_nodes"]], f[c["h1_rel"]], f[c["cpu_time"]], cnt } }' "$csv"
    done
  done
} > "$t/cheapest.csv"

# ---------------------------------------------------------------- master refinement at fixed slave mesh
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; print "level,h1,ratio,nu,dofs,h1_rel,p_l2,F_max,cpu_time,cpu_lemke"; next }
  $(c["status"]) == 0 && $(c["slave"]) == "lower" {
    key = $(c["level"]) "," $(c["ratio"])
    if ($(c["lcp"]) == "pgs") { row[key] = $(c["level"]) "," $(c["h1"]) "," $(c["ratio"]) "," $(c["nu"]) "," $(c["dofs"]) "," \
      $(c["h1_rel"]) "," $(c["p_l2"]) "," $(c["F_max"]) "," $(c["cpu_time"]); keys[key] = 1 }
    else if ($(c["lcp"]) == "lemke") lem[key] = $(c["cpu_time"]) }
  END { for (k in keys) print row[k] "," lem[k] }' "$t/signorini.csv" | { read -r h; echo "$h"; sort -t, -k1,1n -k3,3g; } > "$t/master.csv"

# ---------------------------------------------------------------- slave choice: the same mesh pair, either slave
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
    print "level,nl,nu,err_lower,err_upper,p_l2_lower,p_l2_upper,F_max_lower,F_max_upper,nodes_lower,nodes_upper,time_lower,time_upper"; next }
  $(c["status"]) == 0 && $(c["lcp"]) == "pgs" && $(c["nl"]) != $(c["nu"]) {
    key = $(c["level"]) "," $(c["nl"]) "," $(c["nu"]); keys[key] = 1; s = $(c["slave"])
    e[key, s] = $(c["h1_rel"]); p[key, s] = $(c["p_l2"]); f[key, s] = $(c["F_max"])
    n[key, s] = $(c["contact_nodes"]); tt[key, s] = $(c["cpu_time"]) }
  END { for (k in keys) printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", k, e[k, "lower"], e[k, "upper"], p[k, "lower"],
      p[k, "upper"], f[k, "lower"], f[k, "upper"], n[k, "lower"], n[k, "upper"], tt[k, "lower"], tt[k, "upper"] }' \
  "$t/signorini.csv" | { read -r h; echo "$h"; sort -t, -k1,1n -k3,3n; } > "$t/slave.csv"

# ---------------------------------------------------------------- phase shares
{
  echo "sequence,dofs,contact_nodes,mesh,assemble,factor,condense,lcp,recover,output,other,time_total"
  for seq in S H; do
    if [ $seq = S ]; then csv=$t/signorini.csv; cond='$(c["ratio"]) == 1 && $(c["slave"]) == "lower" && $(c["lcp"]) == "pgs"'
    else csv=$t/hertz.csv; cond='$(c["ratio"]) == 1 && $(c["slave"]) == "block" && $(c["lcp"]) == "pgs"'; fi
    awk -F, -v seq=$seq 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $(c["status"]) == 0 && ('"$cond"') { tot = $(c["time_total"]); s = 0; printf "%s,%s,%s", seq, $(c["dofs"]), $(c["contact_nodes"])
        split("mesh assemble factor condense lcp recover output", ph, " ")
        for (i = 1; i <= 7; i++) { x = $(c["time_" ph[i]]); s += x; printf ",%.3f", x / tot }
        o = (tot - s) / tot; printf ",%.3f,%s\n", (o > 0 ? o : 0), tot }' "$csv" | sort -t, -k2,2n
  done
  for lcp in lemke pgs pdas; do
    awk -F, -v l=$lcp 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $2 == l { split("mesh assemble factor condense lcp recover output", ph, " ")
        tot = 0; for (i = 1; i <= 7; i++) tot += $(c["time_" ph[i]])
        printf "graded %s,%s,%s", l, $(c["dofs"]), $(c["contact_nodes"])
        for (i = 1; i <= 7; i++) printf ",%.3f", $(c["time_" ph[i]]) / tot
        printf ",0,%s\n", $(c["time_total"]) }' "$t/lcp_best.csv" | sort -t, -k2,2n
  done
} > "$t/phases.csv"

# ---------------------------------------------------------------- the LCP solvers against each other
{
  echo "family,config,solvers,active_min,active_max,h1_rel_spread,energy_spread,residual_max,complementarity_max,min_gap_min,cpu_spread,cpu_min"
  for fam in S H; do
    if [ $fam = S ]; then csv=$t/signorini.csv; else csv=$t/hertz.csv; fi
    awk -F, -v fam=$fam 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $(c["status"]) == 0 { k = $(c["name"]); sub(/_(lemke|pgs|pdas)$/, "", k); keys[k] = 1; n[k]++
        a = $(c["active_nodes"]) + 0; e = $(c["h1_rel"]) + 0; en = $(c["energy"]) + 0
        r = $(c["lcp_residual"]) + 0; cp = $(c["complementarity"]) + 0; g = $(c["min_gap"]) + 0; u = $(c["cpu_time"]) + 0
        if (n[k] == 1) { amin[k] = amax[k] = a; emin[k] = emax[k] = e; nmin[k] = nmax[k] = en; rmax[k] = r; cmax[k] = cp; gmin[k] = g
                         umin[k] = umax[k] = u }
        else { if (u < umin[k]) umin[k] = u; if (u > umax[k]) umax[k] = u; if (a < amin[k]) amin[k] = a; if (a > amax[k]) amax[k] = a; if (e < emin[k]) emin[k] = e; if (e > emax[k]) emax[k] = e
               if (en < nmin[k]) nmin[k] = en; if (en > nmax[k]) nmax[k] = en; if (r > rmax[k]) rmax[k] = r
               if (cp > cmax[k]) cmax[k] = cp; if (g < gmin[k]) gmin[k] = g } }
      END { for (k in keys) printf "%s,%s,%d,%d,%d,%.3e,%.3e,%.3e,%.3e,%.3e,%.4f,%.4f\n", fam, k, n[k], amin[k], amax[k],
              (emin[k] > 0 ? (emax[k] - emin[k]) / emin[k] : 0), (nmin[k] > 0 ? (nmax[k] - nmin[k]) / nmin[k] : 0),
              rmax[k], cmax[k], gmin[k], (umin[k] > 0 ? (umax[k] - umin[k]) / umin[k] : 0), umin[k] }' "$csv" | sort
  done
} > "$t/agreement.csv"
