#!/usr/bin/env bash
# Charts of vkcollide_bench CSVs with gnuplot (Debian's gnuplot-nox):
#   tools/bench/plot.sh RESULTS.csv[,MORE.csv] OUTDIR
# frontier.png  per scene, total time per frame against crossing-pair recall: every settings
#               variant is its own series (a new mode appears as soon as the CSV has its rows;
#               the res-N variants form one "resolution" line)
# stages.png    time per stage against triangle count (the default variant)
# layers.png    GPU time against layers peeled (every point)
# Each (scene, variant) is averaged over its frames first; crossing recall is found/total
# crossing pairs summed over the frames. Columns are found by name, so CSVs with other
# column orders (or older ones without found_crossing: recall_crossing is averaged) mix.
set -euo pipefail
csvs="$1"; out="$2"
mkdir -p "$out"
command -v gnuplot >/dev/null || { echo "plot.sh: gnuplot missing (apt-get install gnuplot-nox)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
IFS=, read -r -a files <<< "$csvs"
for f in "${files[@]}"; do grep -v '^#' "$f"; done | awk -F, -v OFS=' ' '
  /^device,/ { delete c; for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { v = $c["variant"]; if (!("found_crossing" in c) && !("set" in c)) v = v "-" $c["backend"]  # issue-7 CSVs
    k = $c["scene"] SUBSEP v; n[k]++; tri[k] = $c["triangles"]; lay[k] += $c["layers"]; res[k] = $c["resolution"]
    s[k] += $c["sampling_ms"]; m[k] += $c["merging_ms"] + $c["separation_ms"]; p[k] += $c["packing_ms"]
    r[k] += $c["readback_ms"]; nw[k] += $c["narrow_ms"]; g[k] += $c["gpu_ms"]; t[k] += $c["total_ms"]
    if ("found_crossing" in c) { fc[k] += $c["found_crossing"]; rc[k] += $c["reference_crossing"] } else { ar[k] += $c["recall_crossing"] } }
  END { for (k in n) { split(k, a, SUBSEP)
    cr = rc[k] > 0 ? fc[k] / rc[k] : (ar[k] > 0 ? ar[k] / n[k] : 1)
    print a[1], a[2], res[k], tri[k], lay[k]/n[k], s[k]/n[k], m[k]/n[k], p[k]/n[k], r[k]/n[k], nw[k]/n[k], g[k]/n[k], t[k]/n[k], cr } }' \
  | sort -k1,1 -k2,2 > "$tmp/points"
# columns: 1 scene 2 variant 3 res 4 tris 5 layers 6 sampling 7 merge+sep 8 packing 9 readback 10 narrow 11 gpu 12 total 13 crossing recall
[ -s "$tmp/points" ] || { echo "plot.sh: no rows in $csvs" >&2; exit 1; }
scenes=$(cut -d' ' -f1 "$tmp/points" | sort -u)
variants=$(cut -d' ' -f2 "$tmp/points" | grep -v '^res-' | sort -u || true)
n=$(echo "$scenes" | wc -l); cols=$(( n < 4 ? n : 4 )); rows=$(( (n + cols - 1) / cols ))
{
  echo "set terminal pngcairo size $((420 * cols)),$((330 * rows + 60)) font ',9'"
  echo "set output '$out/frontier.png'"
  echo "set multiplot layout $rows,$cols title 'Speed against accuracy per scene: total ms per frame (log) vs crossing-pair recall; one series per settings variant'"
  echo "set logscale x; set grid; set key bottom right font ',7'; set yrange [*:1.005]"
  i=0
  for s in $scenes; do
    plots=""
    awk -v s="$s" '$1 == s && $2 ~ /^res-/' "$tmp/points" | sort -k3,3n > "$tmp/res_$i"
    [ -s "$tmp/res_$i" ] && plots="'$tmp/res_$i' using 12:13 with linespoints lc rgb 'gray40' pt 7 title 'resolution sweep',"
    j=0
    for v in $variants; do
      j=$((j + 1))
      awk -v s="$s" -v v="$v" '$1 == s && $2 == v' "$tmp/points" > "$tmp/v_${i}_$j"
      [ -s "$tmp/v_${i}_$j" ] && plots="$plots '$tmp/v_${i}_$j' using 12:13 with points lc $j pt $((j % 13 + 1)) ps 1.5 title '$v',"
    done
    echo "set title '$s' font ',10'"
    echo "plot ${plots%,}"
    i=$((i + 1))
  done
  echo "unset multiplot"
} > "$tmp/frontier.gp"
gnuplot "$tmp/frontier.gp" 2>&1 | { grep -v "empty . range" >&2 || true; }  # one-point panels warn
awk '$2 == "default"' "$tmp/points" | sort -k4,4n > "$tmp/stages"
if [ -s "$tmp/stages" ]; then gnuplot <<GP
set terminal pngcairo size 1000,700
set output '$out/stages.png'
set title 'Time per stage against triangle count (default settings, every scene)'
set xlabel 'triangles (log)'; set ylabel 'ms (log)'; set logscale xy; set key top left; set grid
plot '$tmp/stages' using 4:(\$6 > 0 ? \$6 : 1/0) with points pt 7 title 'sampling (GPU)', \
     '' using 4:(\$7 > 0 ? \$7 : 1/0) with points pt 5 title 'merging + separation (GPU)', \
     '' using 4:(\$8 > 0 ? \$8 : 1/0) with points pt 9 title 'packing (GPU)', \
     '' using 4:(\$9 > 0 ? \$9 : 1/0) with points pt 11 title 'readback (host)', \
     '' using 4:(\$10 > 0 ? \$10 : 1/0) with points pt 13 title 'narrow phase (CPU)', \
     '' using 4:12 with points pt 3 title 'total'
GP
else echo "plot.sh: no default rows: stages.png skipped" >&2; fi
gnuplot <<GP
set terminal pngcairo size 1000,700
set output '$out/layers.png'
set title 'GPU time against layers peeled'
set xlabel 'layers (mean over frames)'; set ylabel 'GPU ms (log)'; set logscale y; set grid; set key top left
plot '$tmp/points' using 5:(\$11 > 0 ? \$11 : 1/0) with points pt 7 title 'every (scene, variant)'
GP
echo "plot.sh: wrote $out/frontier.png $out/stages.png $out/layers.png"
