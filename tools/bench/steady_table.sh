#!/usr/bin/env bash
# docs/results.md's H200 table: per scene, default / peeling / paper-sep, means over frames >= 1.
#   tools/bench/steady_table.sh tuning.csv held-out.csv
exec awk -f - "$@" <<'AWK'
BEGIN{FS=","}
FNR==1{next}
$10>=1 {k=$3 SUBSEP $9; if(!(k in n)){ if(!($3 in seen)){seen[$3]=1; order[++c]=$3; setof[$3]=$2; tri[$3]=$5} } n[k]++; t[k]+=$32-$31; u[k]+=$31; g[k]+=$28; nr[k]+=$30; dl[k]+=$34; fc[k]+=$41; rc[k]+=$40}
END{
 print "| scene | set | triangles | reliable (default): detect ms (GPU, narrow) | + vertex update | read back | crossing recall | peeling, depth-aware: ms, recall | peeling, paper's separation (old default): ms, recall |"
 print "|---|---|---|---|---|---|---|---|---|"
 for(i=1;i<=c;i++){s=order[i]; d=s SUBSEP "default"; p=s SUBSEP "peeling"; q=s SUBSEP "paper-sep";
  printf "| %s | %s | %s | **%.2f** (%.2f, %.2f) | %s | %d | %.2f %% | %.2f, %.2f %% | %.2f, %.2f %% |\n", s, setof[s], tri[s], t[d]/n[d], g[d]/n[d], nr[d]/n[d], (u[d]>0? sprintf("%.2f", u[d]/n[d]) : "–"), dl[d]/n[d], rc[d]?100*fc[d]/rc[d]:100, t[p]/n[p], rc[p]?100*fc[p]/rc[p]:100, t[q]/n[q], rc[q]?100*fc[q]/rc[q]:100}
}
AWK
