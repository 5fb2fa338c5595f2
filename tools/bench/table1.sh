#!/usr/bin/env bash
# The paper's Table 1 from vkcollide_bench CSVs, one markdown row per (scene, variant), means
# over the frames: triangles, collision rays, triangles downloaded, potentially colliding
# triangles, tri-tri tests, positive tests, then GPU (sampling + merging + separation),
# reduce (packing + readback), CPU (narrow phase) and overall ms, and crossing recall. With
# both variants present it adds a row per scene: how many times fewer triangles AFTER
# downloads, and how many more crossing pairs it finds per frame (negative: fewer; from the
# CSV's found-crossing counts, so a recall check, not a pair-by-pair one).
#   tools/bench/table1.sh RESULTS.csv[,MORE.csv] [BEFORE AFTER]   (default: paper-sep depth-sep)
set -euo pipefail
IFS=, read -r -a files <<< "$1"
before="${2:-paper-sep}"; after="${3:-depth-sep}"
echo "| scene | variant | # tri's | # coll. rays | # tri's downl. | # pot. coll. tri's | # tri-tri tests | # pos. tests | GPU ms | reduce ms | CPU ms | overall ms | crossing recall |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for f in "${files[@]}"; do grep -v '^#' "$f"; done | awk -F, -v before="$before" -v after="$after" '
  /^device,/ { delete c; for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $c["variant"] == before || $c["variant"] == after {
    k = $c["scene"] SUBSEP $c["variant"]
    if (!($c["scene"] in seen)) { seen[$c["scene"]] = 1; scenes[++count] = $c["scene"] }
    n[k]++; tri[k] = $c["triangles"]
    rays[k] += $c["collision_rays"]; dl[k] += $c["downloaded"]; pot[k] += $c["pot_colliding"]; tests[k] += $c["tests"]
    pos[k] += $c["positive_tests"]; fc[k] += $c["found_crossing"]; rc[k] += $c["reference_crossing"]
    g[k] += $c["sampling_ms"] + $c["merging_ms"] + $c["separation_ms"]; r[k] += $c["packing_ms"] + $c["readback_ms"]
    cpu[k] += $c["narrow_ms"]; t[k] += $c["total_ms"] }
  END { for (i = 1; i <= count; ++i) { s = scenes[i]
    for (j = 0; j < 2; ++j) { v = j ? after : before; k = s SUBSEP v; m = n[k]; if (!m) continue
      printf "| %s | %s | %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f | %.2f | %.2f | %.2f %% |\n", s, v, tri[k], rays[k] / m,
        dl[k] / m, pot[k] / m, tests[k] / m, pos[k] / m, g[k] / m, r[k] / m, cpu[k] / m, t[k] / m, rc[k] ? 100 * fc[k] / rc[k] : 100 }
    kb = s SUBSEP before; ka = s SUBSEP after
    if (n[kb] && n[ka])
      printf "| %s | %s / %s | | | %.1fx fewer | | | | | | | | crossing pairs found per frame %+.1f |\n", s, before, after,
        dl[ka] ? (dl[kb] / n[kb]) / (dl[ka] / n[ka]) : 0, fc[ka] / n[ka] - fc[kb] / n[kb] } }'
