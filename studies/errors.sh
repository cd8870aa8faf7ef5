#!/bin/sh
# studies/errors.sh OUT JOBS: the error measures of every finished run of
# studies/run-all (OUT/plan.txt), computed as JOBS parallel tasks, then split
# into one file OUT/runs/NAME/metrics per run ("key value" lines).
#   S: broken H1 / energy error against the conforming reference s_ref (c2dh1), over the
#      whole domain and over the interior window W = [0.25, 1.75]^2 (away from the blocks'
#      corners); pressure L2 over x <= 1.75 and the resultant-distribution error
#      (c2derr.py pressure)
#   H: broken H1 / energy error against the reference with the same slave (h_ref: slave =
#      block, h_ref_disk: slave = disk; the two choices are two slightly different contact
#      models, see doc/convergence.md), Hertz a, p0 and the L2 pressure error against the
#      closed form (c2derr.py hertz), pressure L2 against the reference over |x| < a_ref;
#      and OUT/tables/hertz_slave_diff.csv: slave = block against slave = disk on the same
#      meshes, level by level
#   P: stress, pressure and displacement errors against the exact uniform state (patch-errors)
set -eu
out=$1
jobs=$2
st=$(cd "$(dirname "$0")" && pwd)
e=$out/errors
ok() {  # FAMILY [NAME-PATTERN]: the run folders of FAMILY that finished with status 0
  awk -v f="$1" -v p="${2:-.}" '$1 == f && $2 ~ p { print $5 }' "$out/plan.txt" | while read -r d; do
    [ "$(cat "$d/status" 2> /dev/null)" = 0 ] && echo "$d"
  done
}
ok S > "$e/S.dirs"; ok H _block_ > "$e/Hb.dirs"; ok H _disk_ > "$e/Hd.dirs"; ok P > "$e/P.dirs"
cat "$e/Hb.dirs" "$e/Hd.dirs" > "$e/H.dirs"
sref=$out/runs/s_ref; hrefb=$out/runs/h_ref; hrefd=$out/runs/h_ref_disk
for r in "$sref" "$hrefb" "$hrefd"; do
  [ "$(cat "$r/status" 2> /dev/null)" = 0 ] || { echo "errors.sh: reference $r failed" >&2; exit 1; }
done
vtks() { awk '{ n = $0; sub(/.*\//, "", n); print $0 "/" n ".vtk" }' "$1" | tr '\n' ' '; }
csvs() { awk '{ n = $0; sub(/.*\//, "", n); print $0 "/" n "_contact.csv" }' "$1" | tr '\n' ' '; }

# tasks: the H1 errors split in JOBS chunks per list (one reference read per chunk)
i=0
task() { echo "$*" > "$e/task_$i.sh"; i=$(( i + 1 )); }
h1_tasks() {  # LIST REF MATERIAL TAG [OPTIONS]
  list=$1; ref=$2; mat=$3; tag=$4; shift 4
  c=0
  while [ $c -lt "$jobs" ]; do
    awk -v c=$c -v j="$jobs" 'NR % j == c' "$list" > "$e/$tag.$c.dirs"
    [ -s "$e/$tag.$c.dirs" ] && task "\"$out/bin/c2dh1\" -m $mat $* \"$ref\" $(vtks "$e/$tag.$c.dirs") > \"$e/h1_${tag}_$c.csv\""
    c=$(( c + 1 ))
  done
}
h1_tasks "$e/S.dirs" "$sref/s_ref.vtk" 1000,0.3 S
h1_tasks "$e/S.dirs" "$sref/s_ref.vtk" 1000,0.3 Swin --window 0.25,1.75,0.25,1.75
h1_tasks "$e/Hb.dirs" "$hrefb/h_ref.vtk" 200000,0.3 Hb
h1_tasks "$e/Hd.dirs" "$hrefd/h_ref_disk.vtk" 200000,0.3 Hd
task "python3 \"$st/c2derr.py\" pressure \"$sref/s_ref_contact.csv\" $(csvs "$e/S.dirs") --xmax 1.75 > \"$e/p_S.csv\""
pairs=$(awk '{ n = $0; sub(/.*\//, "", n); print $0 "/" n "_contact.csv " $0 "/" n ".summary" }' "$e/H.dirs" | tr '\n' ' ')
task "python3 \"$st/c2derr.py\" hertz \"$hrefb/h_ref_contact.csv\" \"$hrefb/h_ref.summary\" \"$hrefd/h_ref_disk_contact.csv\" \"$hrefd/h_ref_disk.summary\" $pairs --E 200000 --nu 0.3 --R 1 > \"$e/hertz_H.csv\""
task "python3 \"$st/patch-errors\" $(tr '\n' ' ' < "$e/P.dirs") > \"$e/patch_P.csv\""
# slave = block against slave = disk on the same meshes (Lemke), per level, and the two references
for b in $(grep '_r1_block_lemke$' "$e/Hb.dirs"); do
  d=${b%_block_lemke}_disk_lemke
  grep -qx "$d" "$e/Hd.dirs" && echo "$b/$(basename "$b").vtk $d/$(basename "$d").vtk"
done > "$e/slave_pairs.txt"
echo "$hrefb/h_ref.vtk $hrefd/h_ref_disk.vtk" >> "$e/slave_pairs.txt"
echo "$out/runs/h_small_block/h_small_block.vtk $out/runs/h_small_disk/h_small_disk.vtk" >> "$e/slave_pairs.txt"
task "while read -r b d; do \"$out/bin/c2dh1\" -m 200000,0.3 \"\$b\" \"\$d\" | sed \"s|^|\$b,|\"; done < \"$e/slave_pairs.txt\" > \"$e/slave_diff.csv\""
ls "$e"/task_*.sh | xargs -P "$jobs" -n 1 sh

# pressure against the reference profile over |x| < a_ref (a_ref: Hertz a of the reference's load)
for s in b d; do
  if [ $s = b ]; then ref=$hrefb/h_ref_contact.csv; else ref=$hrefd/h_ref_disk_contact.csv; fi
  aref=$(awk -F, -v r="$ref" '$1 == r { print $3 }' "$e/hertz_H.csv")
  python3 "$st/c2derr.py" pressure "$ref" $(csvs "$e/H$s.dirs") --xmin "-$aref" --xmax "$aref" > "$e/p_H$s.csv"
done

# split into OUT/runs/NAME/metrics
split() {  # KEYS... < CSV (first column: a file inside the run folder)
  awk -F, -v keys="$*" 'BEGIN { n = split(keys, k, " ") }
    { d = $1; sub(/\/[^\/]*$/, "", d); f = d "/metrics"
      for (i = 1; i <= n; i++) if (k[i] != "-") print k[i], $(i + 1) >> f
      close(f) }'
}
cat "$e"/h1_S_*.csv "$e"/h1_Hb_*.csv "$e"/h1_Hd_*.csv | split h1_err h1_rel energy_err energy_rel nested h1_body1 h1_body2
cat "$e"/h1_Swin_*.csv | split h1w_err h1w_rel energyw_err energyw_rel
split p_l2 F_l2 F_max < "$e/p_S.csv"
split P a_hertz p0_hertz a_h p0_h a_err p0_err p_l2_hertz < "$e/hertz_H.csv"
cat "$e/p_Hb.csv" "$e/p_Hd.csv" | split p_l2 F_l2 F_max
split stress_err pressure_err u_err < "$e/patch_P.csv"
{
  echo "block_run,disk_run,h1_diff,h1_diff_rel,energy_diff,energy_diff_rel"
  cut -d, -f1-6 "$e/slave_diff.csv" | sed 's|[^,]*/||g; s|\.vtk||g'
} > "$out/tables/hertz_slave_diff.csv"
