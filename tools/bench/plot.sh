#!/usr/bin/env bash
# Charts of vkcollide_bench CSVs with gnuplot (Debian's gnuplot-nox; tools/bench/frontier.sh
# --install-deps installs it):
#   tools/bench/plot.sh RESULTS.csv[,MORE.csv] OUTDIR
# frontier.png  crossing-pair recall against end-to-end ms per frame, one panel per scene kind,
#               every settings variant its own series (tools/bench/frontier.sh: a new mode
#               appears as soon as the CSV has its rows; res-N / cells-N variants form sweep lines;
#               held-out scenes open markers). docs/results.md's chart adds the defaults before
#               and the older sweeps through frontier.sh itself (the command is there).
# stages.png    time per stage against triangle count (the default variant's peeling stages)
# layers.png    GPU time against layers peeled (every point)
# For the stage and layer charts each (scene, variant) is averaged over its frames; columns are
# found by name, so CSVs with other column orders (or older ones without found_crossing) mix.
set -euo pipefail
csvs="$1"; out="$2"
mkdir -p "$out"
command -v gnuplot >/dev/null || { echo "plot.sh: gnuplot missing: tools/bench/frontier.sh --install-deps (apt-get install gnuplot-nox)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
IFS=, read -r -a files <<< "$csvs"
for f in "${files[@]}"; do grep -v '^#' "$f"; done | awk -F, -v OFS=' ' '
  /^device,/ { delete c; for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { v = $c["variant"]; if (!("found_crossing" in c) && !("set" in c)) v = v "-" $c["backend"]  # CSVs of the 2026-11-22 sweep
    k = $c["scene"] SUBSEP v; n[k]++; tri[k] = $c["triangles"]; lay[k] += $c["layers"]; res[k] = $c["resolution"]
    s[k] += $c["sampling_ms"]; m[k] += $c["merging_ms"] + $c["separation_ms"]; p[k] += $c["packing_ms"]
    r[k] += $c["readback_ms"]; nw[k] += $c["narrow_ms"]; g[k] += $c["gpu_ms"]; t[k] += $c["total_ms"] }
  END { for (k in n) { split(k, a, SUBSEP)
    print a[1], a[2], res[k], tri[k], lay[k]/n[k], s[k]/n[k], m[k]/n[k], p[k]/n[k], r[k]/n[k], nw[k]/n[k], g[k]/n[k], t[k]/n[k] } }' \
  | sort -k1,1 -k2,2 > "$tmp/points"
# columns: 1 scene 2 variant 3 res 4 tris 5 layers 6 sampling 7 merge+sep 8 packing 9 readback 10 narrow 11 gpu 12 total
[ -s "$tmp/points" ] || { echo "plot.sh: no rows in $csvs" >&2; exit 1; }
bash "$(dirname "$0")/frontier.sh" "$out/frontier.png" "${files[@]}" >/dev/null
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
