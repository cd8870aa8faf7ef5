#!/bin/sh
# studies/plots.sh OUT IMG: the PNG plots of the studies from OUT/tables into
# IMG (gnuplot, pngcairo; png if pngcairo is missing).  The data files and
# gnuplot scripts stay in OUT/plots for inspection.
set -eu
out=$1
img=$2
t=$out/tables
p=$out/plots
mkdir -p "$p" "$img"
if gnuplot -e 'set terminal' 2>&1 | grep -q pngcairo; then
  term='set terminal pngcairo size 900,640 enhanced font "Sans,11" linewidth 1.5'
  term2='set terminal pngcairo size 1400,600 enhanced font "Sans,11" linewidth 1.5'
else
  term='set terminal png size 900,640'
  term2='set terminal png size 1300,560'
fi
common='set grid; set key top left box opaque; set mxtics 10; set mytics 10; set format x "10^{%L}"; set format y "10^{%L}"'

# sel CSV CONDITION COLUMN...: the named columns of the rows (status 0) meeting
# CONDITION, an awk expression over v("column")
sel() {
  f=$1; cond=$2; shift 2
  awk -F, -v cols="$*" 'function v(name) { return $(c[name]) }
    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; n = split(cols, k, " "); next }
    v("status") == 0 && ('"$cond"') { for (i = 1; i <= n; i++) printf "%s%s", v(k[i]), (i < n ? " " : "\n") }' "$f"
}
# rate SERIES QUANTITY: "rate constant" of a fitted series (rates.csv), or "nan nan"
rate() {
  awk -F, -v s="$1" -v q="$2" '$1 == s && $2 == q { print $4, $5; found = 1 } END { if (!found) print "nan", "nan" }' \
    "$t/rates.csv"
}

# ---------------------------------------------------------------- S: H1 error vs h1
plot=""
i=1
for r in 0.25 0.5 1 2 4; do
  sel "$t/signorini.csv" "v(\"ratio\") == $r && v(\"slave\") == \"lower\" && v(\"lcp\") == \"lemke\"" h1 h1_rel energy_rel \
    | sort -g > "$p/s_h1_$r.dat"
  [ -s "$p/s_h1_$r.dat" ] || continue
  set -- $(rate "S h2/h1=$r slave=lower" h1_rel)
  plot="$plot \"$p/s_h1_$r.dat\" u 1:2 w lp pt $((i + 4)) lc $i t sprintf(\"h2/h1 = $r: rate %.2f\", $1), \
    $2 * x**$1 w l dt 2 lc $i notitle,"
  i=$((i + 1))
done
sel "$t/signorini.csv" 'v("ratio") == 1 && v("slave") == "lower" && v("lcp") == "lemke"' h1 h1w_rel | sort -g > "$p/s_h1w.dat"
set -- $(rate "S h2/h1=1 slave=lower" h1w_rel)
plot="$plot \"$p/s_h1w.dat\" u 1:2 w lp pt 13 ps 1.4 lc rgb \"black\" t sprintf(\"h2/h1 = 1, interior window W: rate %.2f\", $1),"
cat > "$p/s_h1.gp" <<GP
$term
set output "$img/s_h1.png"
$common
set logscale xy
set xlabel "slave mesh size h_1"
set ylabel "relative broken H^1 error |u_{ref} - u_h|_{1,h} / |u_{ref}|_{1,h}"
set title "Signorini S: broken H^1 error against the conforming reference (h = 1/$(awk -F, 'NR == 2 { print $3 / 2 }' "$t/signorini_ref.csv")), slave = lower body"
set key bottom right
plot $plot 0.9 * x**0.75 w l lw 2 lc rgb "gray60" t "h^{3/4} (paper's bound)", 1.4 * x w l lw 2 dt 3 lc rgb "black" t "h^1"
GP
gnuplot "$p/s_h1.gp"

# ---------------------------------------------------------------- S: pressure errors vs h1
plot=""
i=1
for r in 0.5 1 2; do
  sel "$t/signorini.csv" "v(\"ratio\") == $r && v(\"slave\") == \"lower\" && v(\"lcp\") == \"lemke\"" h1 p_l2 F_max F_l2 \
    | sort -g > "$p/s_p_$r.dat"
  [ -s "$p/s_p_$r.dat" ] || continue
  set -- $(rate "S h2/h1=$r slave=lower" p_l2)
  a1=$1; a2=$2
  set -- $(rate "S h2/h1=$r slave=lower" F_max)
  plot="$plot \"$p/s_p_$r.dat\" u 1:2 w lp pt 7 lc $i t sprintf(\"L^2 pressure (x < 1.75), h2/h1 = $r: rate %.2f\", $a1), \
    \"$p/s_p_$r.dat\" u 1:3 w lp pt 5 dt 4 lc $i t sprintf(\"max |F_h - F_{ref}| / F, h2/h1 = $r: rate %.2f\", $1),"
  i=$((i + 1))
done
cat > "$p/s_pressure.gp" <<GP
$term
set output "$img/s_pressure.png"
$common
set logscale xy
set xlabel "slave mesh size h_1"
set ylabel "relative error"
set title "Signorini S: contact pressure against the reference (F(x) = {/Symbol \\362}_x^2 p ds, the resultant distribution)"
set key bottom right
plot $plot 0.5 * x w l lw 2 dt 3 lc rgb "black" t "h^1", 1.5 * x**0.5 w l lw 2 lc rgb "gray60" t "h^{1/2}"
GP
gnuplot "$p/s_pressure.gp"

# ---------------------------------------------------------------- H: H1 error and Hertz measures vs hc
plot=""
i=1
for s in block disk; do
  sel "$t/hertz.csv" "v(\"ratio\") == 1 && v(\"slave\") == \"$s\" && v(\"lcp\") == \"lemke\"" h1 h1_rel energy_rel \
    | sort -g > "$p/h_h1_$s.dat"
  set -- $(rate "H h2/h1=1 slave=$s" h1_rel)
  plot="$plot \"$p/h_h1_$s.dat\" u 1:2 w lp pt $((i + 4)) lc $i t sprintf(\"slave = $s: rate %.2f\", $1), \
    $2 * x**$1 w l dt 2 lc $i notitle,"
  i=$((i + 1))
done
cat > "$p/h_h1.gp" <<GP
$term
set output "$img/h_h1.png"
$common
set logscale xy
set xlabel "near-contact mesh size h_c (both bodies, far size min(0.5, 12.5 h_c))"
set ylabel "relative broken H^1 error |u_{ref} - u_h|_{1,h} / |u_{ref}|_{1,h}"
set title "Hertz H: broken H^1 error against the reference (h_c = $(awk -F, 'NR == 2 { print $3 }' "$t/hertz_ref.csv"))"
set key bottom right
plot $plot 3 * x**0.75 w l lw 2 lc rgb "gray60" t "h^{3/4} (paper's bound)", 4 * x w l lw 2 dt 3 lc rgb "black" t "h^1"
GP
gnuplot "$p/h_h1.gp"

sel "$t/hertz.csv" 'v("ratio") == 1 && v("slave") == "block" && v("lcp") == "lemke"' h1 a_err p0_err p_l2_hertz p_l2 \
  a_err_ref p0_err_ref | sort -g > "$p/h_hertz.dat"
plot=""
col=2
for q in a_err p0_err p_l2_hertz p_l2 a_err_ref p0_err_ref; do
  case $q in
    a_err) lab="a against Hertz";; p0_err) lab="p_0 against Hertz";; p_l2_hertz) lab="L^2 pressure (|x| < a) against Hertz";;
    p_l2) lab="L^2 pressure (|x| < a) against the reference";; a_err_ref) lab="a against the reference";;
    p0_err_ref) lab="p_0 against the reference";;
  esac
  set -- $(rate "H h2/h1=1 slave=block" $q)
  plot="$plot \"$p/h_hertz.dat\" u 1:$col w lp pt $((col + 3)) lc $((col - 1)) t sprintf(\"$lab: rate %.2f\", $1),"
  col=$((col + 1))
done
cat > "$p/h_hertz.gp" <<GP
$term
set output "$img/h_hertz.png"
$common
set logscale xy
set xlabel "near-contact mesh size h_c"
set ylabel "relative error"
set title "Hertz H (slave = block): contact half-width a, peak pressure p_0 and pressure profile"
set key bottom right font ",10"
plot ${plot%,}
GP
gnuplot "$p/h_hertz.gp"

# ---------------------------------------------------------------- axisymmetric Hertz (input/hertz_axi.deck)
if [ -s "$t/axi_hertz_profile.dat" ]; then
  awk -F, 'NR > 1 { print $1, ($5 < 0 ? -$5 : $5), ($7 < 0 ? -$7 : $7), ($8 < 0 ? -$8 : $8), ($9 < 0 ? -$9 : $9) }' \
    "$t/axi_hertz.csv" > "$p/axi_hertz_err.dat"
  cat > "$p/axi_hertz.gp" <<GP
$term2
set output "$img/axi_hertz.png"
set multiplot layout 1,2 title "PLANE axisymmetric: sphere R = 1 on a flat block (input/hertz_axi.deck), P1, E = 200000, nu = 0.3" noenhanced
set grid
set key top right box opaque
set xlabel "r"
set ylabel "contact pressure (per unit area)"
set title "$(head -n 1 "$t/axi_hertz_profile.dat" | sed 's/^# r pressure hertz *//')"
plot "$t/axi_hertz_profile.dat" u 1:3 w l lw 2 lc rgb "gray50" t "Hertz with the computed P", \
     "" u 1:2 w p pt 7 ps 0.6 lc 1 t "contact2d (nodal pressure)"
set logscale xy
set format x "10^{%L}"; set format y "10^{%L}"
set xlabel "near-contact mesh size h_c"
set ylabel "|relative error|"
set title "against Hertz with the computed P"
set key bottom right
plot "$p/axi_hertz_err.dat" u 1:2 w lp pt 5 t "a (second moment)", "" u 1:3 w lp pt 7 t "peak pressure", \
     "" u 1:4 w lp pt 9 t "pressure at the axis node", "" u 1:5 w lp pt 11 t "int p dA against P"
unset multiplot
GP
  gnuplot "$p/axi_hertz.gp"
fi

# ---------------------------------------------------------------- manufactured solution
awk -F, 'NR > 1 && $1 == "tri3" { print $3, $4, $5 }' "$t/mms.csv" > "$p/mms_tri3.dat"
awk -F, 'NR > 1 && $1 == "quad4" { print $3, $4, $5 }' "$t/mms.csv" > "$p/mms_quad4.dat"
if [ -s "$p/mms_tri3.dat" ]; then
  set -- $(rate "manufactured tri3" l2_err); r1=$1
  set -- $(rate "manufactured tri3" h1_err); r2=$1
  set -- $(rate "manufactured quad4" l2_err); r3=$1
  set -- $(rate "manufactured quad4" h1_err); r4=$1
  cat > "$p/mms.gp" <<GP
$term
set output "$img/mms.png"
$common
set logscale xy
set xlabel "mesh size h"
set ylabel "error"
set title "Manufactured solution (plane strain, unit square): errors against the exact solution"
set key bottom right
plot "$p/mms_tri3.dat" u 1:2 w lp pt 7 lc 1 t sprintf("P1 L^2: rate %.2f", $r1), \
     "$p/mms_tri3.dat" u 1:3 w lp pt 5 lc 2 t sprintf("P1 H^1: rate %.2f", $r2), \
     "$p/mms_quad4.dat" u 1:2 w lp pt 6 lc 3 t sprintf("Q1 L^2: rate %.2f", $r3), \
     "$p/mms_quad4.dat" u 1:3 w lp pt 4 lc 4 t sprintf("Q1 H^1: rate %.2f", $r4)
GP
  gnuplot "$p/mms.gp"
fi

# ---------------------------------------------------------------- accuracy-cost fronts
front() {  # IN OUT: the Pareto front (time ascending, error strictly decreasing) of "time error" lines
  sort -g "$1" | awk 'NR == 1 || $2 < best { print; best = $2 }' > "$2"
}
for fam in s h; do
  if [ $fam = s ]; then csv=$t/signorini.csv; lab="Signorini S"; else csv=$t/hertz.csv; lab="Hertz H"; fi
  plot=""
  i=1
  for r in 0.25 0.5 1 2 4; do
    for lcp in lemke pgs pdas; do
      sel "$csv" "v(\"ratio\") == $r && v(\"lcp\") == \"$lcp\"" cpu_time h1_rel contact_nodes > "$p/${fam}_front_${r}_$lcp.dat"
      [ -s "$p/${fam}_front_${r}_$lcp.dat" ] || continue
      case $lcp in lemke) pt=7;; pgs) pt=4;; *) pt=8;; esac
      plot="$plot \"$p/${fam}_front_${r}_$lcp.dat\" u 1:2 w p pt $pt ps 1.3 lc $i notitle,"
    done
    plot="$plot NaN w p pt 7 ps 1.3 lc $i t \"h2/h1 = $r\","
    i=$((i + 1))
  done
  plot="$plot NaN w p pt 7 ps 1.3 lc rgb \"black\" t \"Lemke\", NaN w p pt 4 ps 1.3 lc rgb \"black\" t \"PGS\","
  plot="$plot NaN w p pt 8 ps 1.3 lc rgb \"black\" t \"PDAS\","
  sel "$csv" 'v("h1_rel") != ""' cpu_time h1_rel > "$p/${fam}_all.dat"
  front "$p/${fam}_all.dat" "$p/${fam}_front.dat"
  cat > "$p/${fam}_front.gp" <<GP
$term
set output "$img/${fam}_front.png"
$common
set logscale xy
set xlabel "CPU time of the run (s, one thread)"
set ylabel "relative broken H^1 error"
set title "$lab: accuracy against cost (every mesh pair, ratio, slave choice and LCP solver)"
set key top right font ",10"
plot $plot "$p/${fam}_front.dat" u 1:2 w steps lw 2 lc rgb "black" t "front: cheapest run"
GP
  gnuplot "$p/${fam}_front.gp"
done

# ---------------------------------------------------------------- LCP: Lemke against PGS
for lcp in lemke pgs pdas; do
  awk -F, -v l=$lcp 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $2 == l { print $(c["contact_nodes"]), $(c["time_lcp"]), $(c["time_total"]), $(c["lcp_iterations"]), $(c["time_condense"]) }' \
    "$t/lcp_best.csv" | sort -g > "$p/lcp_$lcp.dat"
  sel "$t/signorini.csv" "v(\"lcp\") == \"$lcp\"" contact_nodes time_lcp time_total | sort -g > "$p/lcp_s_$lcp.dat"
done
cat > "$p/lcp.gp" <<GP
$term2
set output "$img/lcp.png"
$common
set multiplot layout 1,2
set logscale xy
set xlabel "contact nodes n (slave nodes)"
set ylabel "LCP time (s)"
set title "LCP solve time: Lemke, PGS and PDAS (tol 1e-10)"
set key top left font ",10"
plot "$p/lcp_lemke.dat" u 1:2 w lp pt 7 lc 1 t "Lemke, graded S (fastest of the repeats)", \
     "$p/lcp_pgs.dat" u 1:2 w lp pt 5 lc 2 t "PGS, graded S", \
     "$p/lcp_pdas.dat" u 1:2 w lp pt 9 lc 3 t "PDAS, graded S", \
     "$p/lcp_s_lemke.dat" u 1:2 w p pt 6 lc 1 t "Lemke, S sweep runs", \
     "$p/lcp_s_pgs.dat" u 1:2 w p pt 4 lc 2 t "PGS, S sweep runs", \
     "$p/lcp_s_pdas.dat" u 1:2 w p pt 8 lc 3 t "PDAS, S sweep runs", \
     1e-9 * x**3 w l dt 3 lc rgb "gray50" t "n^3", 1e-8 * x**2 w l dt 2 lc rgb "gray50" t "n^2"
set ylabel "share of the total time"
set logscale x
unset logscale y
set format y "%.1f"
set yrange [0:1]
set title "LCP share of the run time (graded S)"
plot "$p/lcp_lemke.dat" u 1:(\$2/\$3) w lp pt 7 lc 1 t "Lemke", \
     "$p/lcp_pgs.dat" u 1:(\$2/\$3) w lp pt 5 lc 2 t "PGS", \
     "$p/lcp_pdas.dat" u 1:(\$2/\$3) w lp pt 9 lc 3 t "PDAS"
unset multiplot
GP
gnuplot "$p/lcp.gp"

# ---------------------------------------------------------------- phase shares as the mesh grows
phases="time_mesh time_assemble time_factor time_condense time_lcp time_recover time_output"
share() {  # CSV CONDITION OUT: dofs and the cumulated shares of the phases, "other" last
  sel "$1" "$2" dofs $phases time_total | sort -g | awk '{ s = 0; printf "%s", $1
    for (i = 2; i <= 8; i++) { s += $i / $9; printf " %.5f", s } printf " 1\n" }' > "$3"
}
share "$t/signorini.csv" 'v("ratio") == 1 && v("slave") == "lower" && v("lcp") == "pgs"' "$p/phases_s.dat"
share "$t/hertz.csv" 'v("ratio") == 1 && v("slave") == "block" && v("lcp") == "pgs"' "$p/phases_h.dat"
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $2 == "lemke" { print $(c["dofs"]), $(c["time_mesh"]),
  $(c["time_assemble"]), $(c["time_factor"]), $(c["time_condense"]), $(c["time_lcp"]), $(c["time_recover"]),
  $(c["time_output"]), $(c["time_mesh"]) + $(c["time_assemble"]) + $(c["time_factor"]) + $(c["time_condense"]) \
  + $(c["time_lcp"]) + $(c["time_recover"]) + $(c["time_output"]) }' "$t/lcp_best.csv" | sort -g | awk '{ s = 0; printf "%s", $1
    for (i = 2; i <= 8; i++) { s += $i / $9; printf " %.5f", s } printf " 1\n" }' > "$p/phases_g.dat"
stack() {  # DAT TITLE
  echo "set title \"$2\""
  echo "plot \\"
  echo "  \"$1\" u 1:8:9 w filledcurves lc rgb \"gray80\" t \"other\", \\"
  k=8
  for ph in output recover lcp condense factor assemble mesh; do
    col=$k
    lo=$((k - 1))
    case $ph in
      mesh) c='#4e79a7';; assemble) c='#f28e2b';; factor) c='#e15759';; condense) c='#76b7b2';;
      lcp) c='#59a14f';; recover) c='#edc948';; output) c='#b07aa1';;
    esac
    if [ $ph = mesh ]; then lower=0; else lower="\$$lo"; fi
    if [ $ph = mesh ]; then end=""; else end=", \\"; fi
    echo "  \"$1\" u 1:($lower):$col w filledcurves lc rgb \"$c\" t \"$ph\"$end"
    k=$((k - 1))
  done
}
{
  echo "$term2"
  echo "set output \"$img/phases.png\""
  echo "set grid; set logscale x; set format x \"10^{%L}\"; set yrange [0:1]; set xlabel \"dofs\"; set ylabel \"share of the total time\""
  echo "set key outside bottom center horizontal maxrows 2 font \",9\""
  echo "set multiplot layout 1,3"
  stack "$p/phases_s.dat" "Signorini S (h2/h1 = 1, PGS)"
  stack "$p/phases_h.dat" "Hertz H (h2/h1 = 1, PGS)"
  stack "$p/phases_g.dat" "graded S, Lemke (n = 13 ... 3073)"
  echo "unset multiplot"
} > "$p/phases.gp"
gnuplot "$p/phases.gp"

# ---------------------------------------------------------------- master refinement at fixed slave mesh
plot1=""; plot2=""
for k in 0 1 2 3 4; do
  sel "$t/signorini.csv" "v(\"level\") == $k && v(\"slave\") == \"lower\" && v(\"lcp\") == \"pgs\"" ratio h1_rel cpu_time p_l2 \
    | sort -g > "$p/master_$k.dat"
  [ -s "$p/master_$k.dat" ] || continue
  h=$(( 12 * (1 << k) ))
  plot1="$plot1 \"$p/master_$k.dat\" u 1:2 w lp pt 7 lc $((k + 1)) t \"h_1 = 1/$((h / 2))\","
  plot2="$plot2 \"$p/master_$k.dat\" u 1:3 w lp pt 7 lc $((k + 1)) t \"h_1 = 1/$((h / 2))\","
done
cat > "$p/master.gp" <<GP
$term2
set output "$img/master.png"
$common
set multiplot layout 1,2
set logscale xy
set format x "%g"
set xtics (0.25, 0.5, 1, 2, 4)
set xlabel "h_2 / h_1 (master over slave mesh size; < 1: master finer)"
set ylabel "relative broken H^1 error"
set title "Signorini S: error at fixed slave mesh as the master is refined"
set key bottom right
plot ${plot1%,}
set ylabel "CPU time of the run (s)"
set title "... and the CPU time (PGS)"
set key top right
plot ${plot2%,}
unset multiplot
GP
gnuplot "$p/master.gp"
