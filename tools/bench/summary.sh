#!/usr/bin/env bash
# The short table of vkcollide_bench CSVs: one markdown row per (set, scene, variant), means
# over the frames; crossing recall and recall are found / total pairs summed over frames.
#   tools/bench/summary.sh RESULTS.csv[,MORE.csv] [VARIANT_REGEX] [short]
# "short": set, scene, triangles, variant, resolution, crossing recall, recall, triangles
# downloaded and total ms only.
set -euo pipefail
IFS=, read -r -a files <<< "$1"
pick="${2:-.}"; short="${3:-}"
if [ "$short" = short ]; then
  echo "| set | scene | tris | variant | res | crossing recall | recall | tri's downl. | total ms |"
  echo "|---|---|---|---|---|---|---|---|---|"
else
  echo "| set | scene | tris | variant | backend | res | crossing recall | recall | precision | coll. rays | tri's downl. | tri-tri tests | sampling | merge+sep | packing | readback | narrow | update | total ms | GPU MiB |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
fi
for f in "${files[@]}"; do grep -v '^#' "$f"; done | awk -F, -v pick="$pick" -v short="$short" '
  /^device,/ { delete c; for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $c["variant"] ~ pick {
    k = $c["set"] SUBSEP $c["scene"] SUBSEP $c["variant"]
    if (!(k in n)) order[++count] = k
    n[k]++; tri[k] = $c["triangles"]; be[k] = $c["backend"]; res[k] = $c["resolution"]
    fc[k] += $c["found_crossing"]; rc[k] += $c["reference_crossing"]; fp[k] += $c["recall"] * $c["reference_pairs"]; rp[k] += $c["reference_pairs"]
    if (n[k] == 1 || $c["precision"] < pmin[k]) pmin[k] = $c["precision"]
    rays[k] += $c["collision_rays"]; dl[k] += $c["downloaded"]; tests[k] += $c["tests"]
    s[k] += $c["sampling_ms"]; ms[k] += $c["merging_ms"] + $c["separation_ms"]; p[k] += $c["packing_ms"]; rb[k] += $c["readback_ms"]
    nw[k] += $c["narrow_ms"]; u[k] += $c["update_ms"]; t[k] += $c["total_ms"]; mem[k] = $c["gpu_mib"] }
  END { for (i = 1; i <= count; ++i) { k = order[i]; split(k, a, SUBSEP); m = n[k]
    if (short == "short") {
      printf "| %s | %s | %s | %s | %s | %.2f %% | %.2f %% | %.0f | %.2f |\n", a[1], a[2], tri[k], a[3], res[k],
        rc[k] ? 100 * fc[k] / rc[k] : 100, rp[k] ? 100 * fp[k] / rp[k] : 100, dl[k] / m, t[k] / m
      continue
    }
    printf "| %s | %s | %s | %s | %s | %s | %.2f %% | %.2f %% | %.2f %% | %.0f | %.0f | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f | %.0f |\n",
      a[1], a[2], tri[k], a[3], be[k], res[k], rc[k] ? 100 * fc[k] / rc[k] : 100, rp[k] ? 100 * fp[k] / rp[k] : 100, 100 * pmin[k],
      rays[k] / m, dl[k] / m, tests[k] / m, s[k] / m, ms[k] / m, p[k] / m, rb[k] / m, nw[k] / m, u[k] / m, t[k] / m, mem[k] } }'
