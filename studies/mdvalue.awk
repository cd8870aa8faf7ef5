# mdvalue.awk: the column `col` of the first row meeting selected(), printed
# with the format f (studies/mkdoc.sh, function val).
function v(name) { return $(c[name]) }
NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
!done && selected() { printf f, v(col); done = 1 }
