# mdtable.awk: a Markdown table from a CSV with a header line.
#   awk -F, -v cols='h1:h_1:%.4g level:k:%d ...' -f mdtable.awk -f SELECT.awk FILE.csv
# SELECT.awk defines `function selected() { return (CONDITION) }`, CONDITION
# an expression over v("column") (studies/mkdoc.sh writes it); rows with a
# status column other than 0 are always left out.  cols:
# space-separated column:header:format triples (header underscores become
# spaces unless escaped as \_; format a printf format, or "s" for text).
# Special columns: "rate(E,H)" is the observed rate log(E_prev/E)/log(H_prev/H)
# against the previous selected row (blank on the first, and where H does not
# decrease: a new series); "ratio(A,B)" is A/B.
function v(name) { return $(c[name]) }
function cell(spec,    s, a, b, k) {
    if (spec ~ /^rate\(/) {
        s = substr(spec, 6, length(spec) - 6); split(s, k, ",")
        a = v(k[1]); b = v(k[2])
        if (have_prev && a > 0 && prev[k[1]] > 0 && prev[k[2]] > b)
            s = log(prev[k[1]] / a) / log(prev[k[2]] / b)
        else
            s = ""
        return s
    }
    if (spec ~ /^ratio\(/) {
        s = substr(spec, 7, length(spec) - 7); split(s, k, ",")
        return (v(k[2]) != 0 && v(k[2]) != "") ? v(k[1]) / v(k[2]) : ""
    }
    return v(spec)
}
function fmt(f, x) {
    if (x == "") return ""
    if (f == "s") return x
    return sprintf(f, x)
}
BEGIN {
    n = split(cols, spec, " ")
    for (i = 1; i <= n; i++) {
        m = split(spec[i], p, ":")
        col[i] = p[1]; head[i] = p[2]; form[i] = (m >= 3) ? p[3] : "s"
        gsub(/\\_/, "\001", head[i]); gsub(/_/, " ", head[i]); gsub(/\001/, "_", head[i])
    }
    line = "|"; sep = "|"
    for (i = 1; i <= n; i++) { line = line " " head[i] " |"; sep = sep (form[i] == "s" ? " --- |" : " ---: |") }
    print line; print sep
}
NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
("status" in c) && v("status") != 0 { next }
{
    if (!selected()) next
    line = "|"
    for (i = 1; i <= n; i++) line = line " " fmt(form[i], cell(col[i])) " |"
    print line
    for (name in c) prev[name] = v(name)
    have_prev = 1
}
