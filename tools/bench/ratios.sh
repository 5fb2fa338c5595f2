#!/usr/bin/env bash
# vkcollide against the peers, scene by scene, from the two benchmarks' CSVs taken on the
# same machine (same scenes, same frames: tools/bench/bench_scenes):
#   tools/bench/ratios.sh VKCOLLIDE.csv[,MORE.csv] PEERS.csv[,MORE.csv] [VARIANT] [RESOLUTION]
# For each scene: vkcollide's mean total time per frame for the chosen variant (default:
# "default", the automatic settings; RESOLUTION, if given, also filters on the resolution that
# ran) and its crossing recall, then each peer's median total time per frame (self-collision
# mode, every peer that ran it) and the ratio peer / vkcollide. The 2026-11-22 sweep's CSVs (variant
# "single", a backend column) still work: pass VARIANT single and RESOLUTION 1024.
set -euo pipefail
ours="$1"; peers="$2"; variant="${3:-default}"; res="${4:-}"
cat_csv() { local IFS=,; for f in $1; do grep -v '^#' "$f"; done; }
cat_csv "$ours" | awk -F, -v v="$variant" -v r="$res" '
  $1 == "device" { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $c["variant"] == v && (r == "" || $c["resolution"] == r) && (!("backend" in c) || ("set" in c) || $c["backend"] == "compute") {
    k = $c["scene"]; t[k] += $c["total_ms"]; g[k] += $c["gpu_ms"]; nw[k] += $c["narrow_ms"]; n[k]++
    rc[k] += ("recall_crossing" in c) ? $c["recall_crossing"] : $c["recall"] }
  END { for (k in n) printf "ours %s %.3f %.3f %.3f %.4f\n", k, t[k]/n[k], g[k]/n[k], nw[k]/n[k], rc[k]/n[k] }' > /tmp/ratios_ours.$$
cat_csv "$peers" | awk -F, '
  $1 == "scene" { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $c["mode"] ~ /-(self|between)$/ { print $c["scene"], $c["peer"], $c["mode"], $c["total_ms"] }' |
  sort -k1,1 -k2,2 -k3,3 -k4,4g |
  awk '{ k = $1 " " $2 " " $3; if (k != prev && prev != "") out(); if (k != prev) n = 0; prev = k; v[++n] = $4 }
       function out() { printf "peer %s %.3f\n", prev, (n % 2) ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2 }
       END { if (prev != "") out() }' > /tmp/ratios_peers.$$
echo "| scene | vkcollide total ms (GPU + narrow) | crossing recall | peer (mode) | peer ms | peer / vkcollide |"
echo "|---|---|---|---|---|---|"
while read -r _ scene total gpu narrow recall; do
  grep "^peer $scene " /tmp/ratios_peers.$$ | sort -k5,5n | while read -r _ _ peer mode ms; do
    awk -v s="$scene" -v t="$total" -v g="$gpu" -v nw="$narrow" -v r="$recall" -v p="$peer" -v m="$mode" -v ms="$ms" \
      'BEGIN { printf "| %s | %.2f (%.2f + %.2f) | %.2f %% | %s (%s) | %.2f | %.1f× |\n", s, t, g, nw, 100 * r, p, m, ms, ms / t }'
  done
done < <(sort -k2 /tmp/ratios_ours.$$)
rm -f /tmp/ratios_ours.$$ /tmp/ratios_peers.$$
