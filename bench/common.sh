# bench/common.sh: what every benchmark script shares, sourced after $top is
# set.
#   median    the median of the numbers on standard input, one per line
#   key FILE KEY
#             the first value of the summary line KEY in FILE
#   runs NAME FILE AWK [N]
#             N runs (default $reps) of $work/NAME.deck by $prog into
#             $work/out, with --no-mesh-cache (every run meshes its .geo, as
#             the first run of a deck does: a repeated run would read the
#             mesh cache); after each, what the awk program AWK prints from
#             the run's summary is appended to FILE (emptied first).  The
#             caller sets prog, work and reps.
#   run NAME [N]
#             runs of NAME keeping cpu_total, the run's CPU seconds with
#             gmsh's included; $work/NAME.cpu holds their median
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }
key() { awk -v k="$2" '$1 == k {print $2; exit}' "$1"; }
runs() {
  rm -f "$2"
  i=0
  while [ "$i" -lt "${4:-$reps}" ]; do
    "$prog" -q --no-mesh-cache -o "$work/out" "$work/$1.deck"
    awk "$3" "$work/out/$1.summary" >> "$2"
    i=$((i + 1))
  done
}
run() {
  runs "$1" "$work/$1.t" '$1 == "cpu_total" {print $2; exit}' "${2:-$reps}"
  median < "$work/$1.t" > "$work/$1.cpu"
}
