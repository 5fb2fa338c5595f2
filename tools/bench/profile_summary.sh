#!/usr/bin/env bash
# A "where the time goes" table with the cell stage's passes: one row per scene from the text that
# tools/bench/profile_table.sh prints for the reliable method (variant default).
#   tools/bench/profile_summary.sh TABLE.txt...
# Columns (ms, means over frames >= 1): GPU = the sum of the passes' timestamps; the cell
# stage's four big passes; the narrow phase and three of its stages; "other host" = the host
# part of detect() beyond the GPU passes (settings, recording, submission, launch and wake-up
# latency, gaps between passes); the vertex update; end to end (update + detect).
echo "| scene | GPU | cells-setup | cells-fill | cells-sweep | cells-pairs | narrow | validate | test | response | other host | update | end to end |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
exec awk '/ \/ default/{s=$1} /gpu:/{g[s]+=$2} /gpu:cells-setup/{su[s]=$2} /gpu:cells-fill/{fi[s]=$2} /gpu:cells-sweep/{sw[s]=$2}
  /gpu:cells-pairs/{pa[s]=$2} /narrow:validate/{va[s]=$2} /narrow:test/{te[s]=$2} /narrow:response/{re[s]=$2} /narrow:total/{nt[s]=$2}
  /host:start/{st[s]=$2} /host:update/{up[s]=$2} /host:total/{to[s]=$2; o[++n]=s}
  END{for(i=1;i<=n;i++){s=o[i]; printf "| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | **%.2f** |\n",
      s, g[s], su[s], fi[s], sw[s], pa[s], nt[s], va[s], te[s], re[s], st[s]-g[s], up[s], to[s]}}' "$@"
