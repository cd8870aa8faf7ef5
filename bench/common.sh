# bench/common.sh: what every benchmark script shares, sourced after $top is
# set.
#   median    the median of the numbers on standard input, one per line
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }
