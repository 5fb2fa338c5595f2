#!/usr/bin/env bash
# Charts of a vkcollide_bench CSV with gnuplot (Debian's gnuplot-nox):
#   tools/bench/plot.sh RESULTS.csv OUTDIR
# frontier.png  total time per frame against recall (the speed-accuracy frontier), per scene
# stages.png    time per stage against triangle count (single peeling, 1024²)
# layers.png    GPU time against layers peeled (every point of every scene)
# Each (scene, variant, resolution) is averaged over its frames first.
set -euo pipefail
csv="$1"; out="$2"
mkdir -p "$out"
command -v gnuplot >/dev/null || { echo "plot.sh: gnuplot missing (apt-get install gnuplot-nox)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# Columns by name, so the script survives new columns.
awk -F, -v OFS=' ' 'NR==1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { k = $c["scene"] SUBSEP $c["variant"] "-" $c["backend"] SUBSEP $c["resolution"]; n[k]++
    tri[k] = $c["triangles"]; lay[k] = $c["layers"]
    s[k] += $c["sampling_ms"]; m[k] += $c["merging_ms"] + $c["separation_ms"]; p[k] += $c["packing_ms"]
    r[k] += $c["readback_ms"]; nw[k] += $c["narrow_ms"]; g[k] += $c["gpu_ms"]; t[k] += $c["total_ms"]; rc[k] += $c["recall"] }
  END { for (k in n) { split(k, a, SUBSEP)
    print a[1], a[2], a[3], tri[k], lay[k], s[k]/n[k], m[k]/n[k], p[k]/n[k], r[k]/n[k], nw[k]/n[k], g[k]/n[k], t[k]/n[k], rc[k]/n[k] } }' \
  "$csv" | sort -k1,1 -k2,2 -k3,3n > "$tmp/points"
# columns: 1 scene 2 variant 3 res 4 tris 5 layers 6 sampling 7 merge+sep 8 packing 9 readback 10 narrow 11 gpu 12 total 13 recall
scenes=$(cut -d' ' -f1 "$tmp/points" | sort -u)
plots=""
for s in $scenes; do
  for b in raster compute; do
    awk -v s="$s" -v v="single-$b" '$1 == s && $2 == v' "$tmp/points" > "$tmp/f_${s}_$b"
    [ -s "$tmp/f_${s}_$b" ] && plots="$plots '$tmp/f_${s}_$b' using 12:13 with linespoints title '$s ($b)',"
  done
done
gnuplot <<GP
set terminal pngcairo size 1000,700
set output '$out/frontier.png'
set title 'Speed against accuracy: total time per frame vs recall (resolution 256..4096, single peeling, raster and compute)'
set xlabel 'total time per frame, ms (log)'; set ylabel 'recall vs exact reference'
set logscale x; set key bottom right; set grid
plot ${plots%,}
GP
awk '$2 == "single-compute" && $3 == 1024' "$tmp/points" | sort -k4,4n > "$tmp/stages"
[ -s "$tmp/stages" ] || echo "plot.sh: no single-compute 1024 points: stages.png skipped" >&2
[ -s "$tmp/stages" ] && gnuplot <<GP
set terminal pngcairo size 1000,700
set output '$out/stages.png'
set title 'Time per stage against triangle count (single peeling, compute sampling, 1024^2)'
set xlabel 'triangles (log)'; set ylabel 'ms (log)'; set logscale xy; set key top left; set grid
plot '$tmp/stages' using 4:6 with linespoints title 'sampling (GPU)', \
     '' using 4:7 with linespoints title 'merging + separation (GPU)', \
     '' using 4:8 with linespoints title 'packing (GPU)', \
     '' using 4:9 with linespoints title 'readback (host)', \
     '' using 4:10 with linespoints title 'narrow phase (CPU)'
GP
gnuplot <<GP
set terminal pngcairo size 1000,700
set output '$out/layers.png'
set title 'GPU time against layers peeled'
set xlabel 'layers'; set ylabel 'GPU ms (log)'; set logscale y; set grid; set key top left
plot '$tmp/points' using 5:11 with points pt 7 title 'every (scene, variant, resolution)'
GP
echo "plot.sh: wrote $out/frontier.png $out/stages.png $out/layers.png"
