#!/bin/sh
# studies/collect.sh OUT: the CSV tables of studies/run-all from the plan, the
# summaries and the metrics of every run, into OUT/tables:
#   signorini.csv hertz.csv lcp.csv patch.csv  one row per run (failed runs: status != 0)
#   lcp_best.csv                               LCP sweep, the fastest of the repeats
#   mms.csv                                    the manufactured solution's error table
#   meshes.csv                                 the gmsh meshes: nodes, wall and CPU time of gmsh
#   rates.csv                                  least-squares rates (log error vs log h)
set -eu
out=$1
t=$out/tables
phases="time_mesh time_assemble time_factor time_condense time_lcp time_recover time_output time_total cpu_time maxrss_mb \
  lcp_residual complementarity min_gap min_pressure energy"

# table FAMILY COLUMNS...: one CSV row per run of FAMILY (meta from the plan,
# then the summary's keys, then the metrics; the load of Hertz runs as P)
table() {
  fam=$1; shift
  echo "$*" | tr ' ' ','
  awk -v f="$fam" '$1 == f { print $2, $5, $6 }' "$out/plan.txt" | while read -r name dir meta; do
    {
      echo "name $name"
      echo "status $(cat "$dir/status" 2> /dev/null || echo missing)"
      echo "$meta" | tr ',' '\n' | tr '=' ' '
      [ -f "$dir/$name.summary" ] && awk '$1 != "reaction"' "$dir/$name.summary"
      [ -f "$dir/metrics" ] && cat "$dir/metrics"
      [ -f "$dir/cpu" ] && tail -1 "$dir/cpu" | awk 'NF == 4 { print "wall_time", $1; print "cpu_time", $2 + $3; print "maxrss_mb", $4 / 1024 }'
    } | awk -v cols="$*" 'BEGIN { n = split(cols, c, " ") }
        { v[$1] = $2 }
        END { for (i = 1; i <= n; i++) printf "%s%s", (i > 1 ? "," : ""), v[c[i]]; printf "\n" }'
  done
}

table S name status level nl nu slave lcp h1 h2 ratio dofs contact_nodes active_nodes lcp_iterations \
  h1_err h1_rel energy_err energy_rel nested h1_body1 h1_body2 h1w_err h1w_rel energyw_err energyw_rel p_l2 F_l2 F_max $phases > "$t/signorini.csv"
table H name status level hc hb hd slave lcp h1 h2 ratio dofs contact_nodes active_nodes lcp_iterations \
  h1_err h1_rel energy_err energy_rel nested h1_body1 h1_body2 P a_hertz p0_hertz a_h p0_h a_err p0_err p_l2_hertz \
  p_l2 F_l2 F_max $phases > "$t/hertz.csv"
table Href name status hc slave dofs contact_nodes active_nodes lcp_iterations P a_hertz p0_hertz a_h p0_h a_err p0_err \
  p_l2_hertz $phases > "$t/hertz_ref.csv"
table Sref name status n dofs contact_nodes active_nodes lcp_iterations $phases > "$t/signorini_ref.csv"
table G name status n lcp rep dofs contact_nodes active_nodes lcp_iterations $phases > "$t/lcp.csv"
table P name status case ns nm dofs contact_nodes active_nodes stress_err pressure_err u_err > "$t/patch.csv"

# Hertz: a and p0 against the reference's own (a_h, p0_h, same slave), the discretisation part of the error
awk -F, 'NR == FNR { if (FNR == 1) { for (i = 1; i <= NF; i++) r[$i] = i; next }
                     ar[$(r["slave"])] = $(r["a_h"]); pr[$(r["slave"])] = $(r["p0_h"]); next }
  FNR == 1 { print $0 ",a_err_ref,p0_err_ref"; for (i = 1; i <= NF; i++) c[$i] = i; next }
  { a = $(c["a_h"]); p = $(c["p0_h"]); s = $(c["slave"]); A = ar[s]; Q = pr[s]
    printf "%s,%s,%s\n", $0, (a == "" || A == "" ? "" : sprintf("%.6e", (a > A ? a - A : A - a) / A)),
      (p == "" || Q == "" ? "" : sprintf("%.6e", (p > Q ? p - Q : Q - p) / Q)) }' \
  "$t/hertz_ref.csv" "$t/hertz.csv" > "$t/hertz.tmp" && mv "$t/hertz.tmp" "$t/hertz.csv"

# LCP sweep: the fastest of the repeats, phase by phase (interference from other
# work only ever adds time, so the minimum is the robust estimate)
head -1 "$t/lcp.csv" | awk -F, '{ printf "n,lcp,repeats"; for (i = 6; i <= NF; i++) printf ",%s", $i; printf "\n" }' \
  > "$t/lcp_best.csv"
awk -F, 'NR > 1 && $2 == 0 { key = $3 "," $4; m = ++cnt[key]
    for (i = 6; i <= NF; i++) if (m == 1 || $i + 0 < best[key, i]) best[key, i] = $i + 0; nf = NF }
  END { for (key in cnt) { printf "%s,%d", key, cnt[key]; for (i = 6; i <= nf; i++) printf ",%.6g", best[key, i]; printf "\n" } }' \
  "$t/lcp.csv" | sort -t, -k1,1n -k2,2 >> "$t/lcp_best.csv"

# gmsh meshes
{
  echo "mesh,refined,parameters,nodes,gmsh_wall,gmsh_cpu"
  while read -r cost m geo refine args; do
    nodes=$(awk '/^\$Nodes/ { getline; print $2; exit }' "$m" 2> /dev/null)
    tm=$(cat "$m.time" 2> /dev/null || echo "")
    echo "$(basename "$m" .msh),$refine,$(echo "$args" | tr ' ' ';'),$nodes,$(echo "$tm" | awk '{ printf "%s,%.3f", $1, $2 + $3 }')"
  done < "$out/meshes.txt"
} | { read -r h; echo "$h"; sort; } > "$t/meshes.csv"

# manufactured solution (unit test table)
awk 'BEGIN { print "element,n,h,l2_err,h1_err" }
  /^# (tri3|quad4):/ { el = $2; sub(":", "", el); next }
  /^# +[0-9]+ / { printf "%s,%s,%s,%s,%s\n", el, $2, $3, $4, $5 }' "$out/mms.txt" > "$t/mms.csv"

# rates: least squares of log(err) on log(h) per series; series = FILE:FILTER:HCOL:ECOL
fit() {  # NAME CSV HCOL ECOL FILTER(awk condition on columns c[...]) [LEVELMIN [LEVELMAX]]
  awk -F, -v name="$1" -v hc="$3" -v ec="$4" -v lmin="${6:-0}" -v lmax="${7:-99}" '
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $(c["status"]) == 0 && ('"$5"') && $(c[ec]) > 0 && ($(c["level"]) + 0) >= lmin && ($(c["level"]) + 0) <= lmax {
      x = log($(c[hc])); y = log($(c[ec])); n++; sx += x; sy += y; sxx += x * x; sxy += x * y
      if (n == 1 || $(c[hc]) > hmax) hmax = $(c[hc]); if (n == 1 || $(c[hc]) < hmin) hmin = $(c[hc]) }
    END { if (n >= 2) { r = (n * sxy - sx * sy) / (n * sxx - sx * sx); a = (sy - r * sx) / n
            printf "%s,%s,%d,%.4f,%.6e,%.6g,%.6g\n", name, ec, n, r, exp(a), hmin, hmax } }' "$2"
}
{
  echo "series,quantity,points,rate,constant,hmin,hmax"
  for r in 0.25 0.5 1 2 4; do
    for q in h1_rel energy_rel h1w_rel energyw_rel p_l2 F_l2 F_max; do
      fit "S h2/h1=$r slave=lower" "$t/signorini.csv" h1 $q "\$(c[\"ratio\"]) == $r && \$(c[\"slave\"]) == \"lower\" && \$(c[\"lcp\"]) == \"lemke\""
    done
    fit "S h2/h1=$r slave=upper" "$t/signorini.csv" h1 h1_rel "\$(c[\"ratio\"]) == $r && \$(c[\"slave\"]) == \"upper\" && \$(c[\"lcp\"]) == \"lemke\""
  done
  fit "S h2/h1=1 slave=lower levels>=1" "$t/signorini.csv" h1 h1_rel "\$(c[\"ratio\"]) == 1 && \$(c[\"slave\"]) == \"lower\" && \$(c[\"lcp\"]) == \"lemke\"" 1
  fit "S h2/h1=1 slave=lower levels>=1" "$t/signorini.csv" h1 p_l2 "\$(c[\"ratio\"]) == 1 && \$(c[\"slave\"]) == \"lower\" && \$(c[\"lcp\"]) == \"lemke\"" 1
  for s in block disk; do
    for q in h1_rel energy_rel p_l2 p_l2_hertz a_err p0_err a_err_ref p0_err_ref F_max; do
      fit "H h2/h1=1 slave=$s" "$t/hertz.csv" h1 $q "\$(c[\"ratio\"]) == 1 && \$(c[\"slave\"]) == \"$s\" && \$(c[\"lcp\"]) == \"lemke\""
    done
  done
  for s in block disk; do
    for q in h1_rel p_l2; do
      fit "H h2/h1=1 slave=$s levels<=3" "$t/hertz.csv" h1 $q "\$(c[\"ratio\"]) == 1 && \$(c[\"slave\"]) == \"$s\" && \$(c[\"lcp\"]) == \"lemke\"" 0 3
    done
  done
  for el in tri3 quad4; do
    for q in l2_err h1_err; do
      awk -F, -v el=$el 'NR == 1 || $1 == el { if (NR == 1) print $0 ",status,level"; else print $0 ",0,0" }' "$t/mms.csv" > "$t/mms.tmp"
      fit "manufactured $el" "$t/mms.tmp" h $q 1
    done
  done
  rm -f "$t/mms.tmp"
} > "$t/rates.csv"
