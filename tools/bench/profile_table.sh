#!/usr/bin/env bash
# Where each frame's time went: means over frames >= 1 of every stage in a
# `vkcollide_bench --profile FILE` output, one row per scene and variant.
#   tools/bench/profile_table.sh profile.csv [variant]
# Columns: the GPU passes (timestamps) in the order they ran, then the narrow phase's
# stages, the host totals (wall clock) and the detection's host parts (detect:*, DetectStats'
# host_*_ms, gpu_span_ms, launch_wake_ms; detect:rest is total_ms outside the named parts).
exec awk -v want="${2:-}" -f - "$1" <<'AWK'
BEGIN{FS=","}
FNR==1{next}
$4>=1 && (want=="" || $3==want) {
  row=$2 " / " $3; col=$5 ":" $6
  if(!(row in seen)){seen[row]=1; rows[++nr]=row}
  if(!(col in cseen)){cseen[col]=1; cols[++nc]=col}
  key=row SUBSEP col; sum[key]+=$7; cnt[key]++
}
END{
  for(r=1;r<=nr;r++){
    printf "%s\n", rows[r]
    for(c=1;c<=nc;c++){k=rows[r] SUBSEP cols[c]; if(cnt[k]) printf "  %-24s %9.3f\n", cols[c], sum[k]/cnt[k]}
  }
}
AWK
