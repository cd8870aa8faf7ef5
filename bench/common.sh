# bench/common.sh: what every benchmark script shares, sourced after $top is
# set.
#   median    the median of the numbers on standard input, one per line
#   key FILE KEY
#             the first value of the summary line KEY in FILE
#   run NAME [N]
#             N runs (default $reps) of $work/NAME.deck by $prog into
#             $work/out, with --no-mesh-cache (every run meshes its .geo, as
#             the first run of a deck does: a repeated run would read the
#             mesh cache); $work/NAME.cpu holds the median cpu_total, the
#             run's CPU seconds with gmsh's included.  The caller sets prog,
#             work and reps (a script's own key, friction.sh's with its
#             arguments the other way round, does not change it).
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }
key() { awk -v k="$2" '$1 == k {print $2; exit}' "$1"; }
run() {
  rm -f "$work/$1.t"
  i=0
  while [ "$i" -lt "${2:-$reps}" ]; do
    "$prog" -q --no-mesh-cache -o "$work/out" "$work/$1.deck"
    awk '$1 == "cpu_total" {print $2; exit}' "$work/out/$1.summary" >> "$work/$1.t"
    i=$((i + 1))
  done
  median < "$work/$1.t" > "$work/$1.cpu"
}
