#!/usr/bin/env bash
# The bench-set sweep on the GPU machine, in one go: exact references of every scene (cached),
# the tuning set with the defaults, the mitigations, both backends and a resolution sweep, the
# held-out set with the defaults and the strongest mitigations, then a short table.
#
#   tools/bench/run_h200.sh [OUT [PHASES]]
#     OUT     folder for the CSVs and logs (default: $OUT if set, else bench-out)
#     PHASES  any of: references tuning held-out (default: all three, in that order)
#   Environment: BENCH (default build/tools/vkcollide_bench), DATA (data/cgal),
#   CACHE (reference cache, default bench-cache), THREADS (16), FRAMES (rigid repetitions, 3),
#   SCALE (1), TUNING_VARIANTS / HELD_OUT_VARIANTS (override the lists below),
#   EXTRA_VARIANTS (e.g. "reliable,depth-sep" once those variants exist: added to both sets).
#
# Each phase stays well under 10 minutes on the H200 host (estimate: references 1 min on 16
# cores, tuning 3-5 min, held-out 1-2 min; every row is written as soon as it is measured, so
# a killed phase keeps what it did). To stay inside one command's limit, run the phases as
# separate commands:  run_h200.sh "$OUT" references tuning;  run_h200.sh "$OUT" held-out
#
# Needs on the GPU machine: the bench binary built here (Release), data/cgal from
# tools/fetch_cgal_data.sh, and a Vulkan driver (VK_DRIVER_FILES as results/h200_2026-11-29/README.md says).
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-${OUT:-bench-out}}"; shift || true
phases="${*:-references tuning held-out}"
bench="${BENCH:-build/tools/vkcollide_bench}"
data="${DATA:-data/cgal}"; cache="${CACHE:-bench-cache}"; threads="${THREADS:-16}"; frames="${FRAMES:-3}"; scale="${SCALE:-1}"
extra="${EXTRA_VARIANTS:+,$EXTRA_VARIANTS}"
mkdir -p "$out"
common=(--data "$data" --cache "$cache" --threads "$threads" --frames "$frames" --scale "$scale")
status=0
for phase in $phases; do
  start=$(date +%s)
  case "$phase" in
    references)
      "$bench" --reference-only --set all "${common[@]}" | tee "$out/references.txt" || status=1 ;;
    tuning)
      "$bench" --set tuning --variants "${TUNING_VARIANTS:-default,mitigations,backends,resolutions}$extra" --resolutions 1024,2048,4096 \
        "${common[@]}" --csv "$out/tuning.csv" | tee "$out/tuning.txt" || status=1 ;;
    held-out)
      "$bench" --set held-out --variants "${HELD_OUT_VARIANTS:-default,axes3-best,res-2048,res-4096}$extra" --resolutions 2048,4096 \
        "${common[@]}" --csv "$out/held_out.csv" | tee "$out/held_out.txt" || status=1 ;;
    *) echo "run_h200.sh: unknown phase '$phase' (references, tuning, held-out)" >&2; exit 2 ;;
  esac
  echo "run_h200.sh: $phase took $(( $(date +%s) - start )) s" | tee -a "$out/phases.txt"
done
csvs=$(ls "$out"/tuning.csv "$out"/held_out.csv 2>/dev/null | paste -sd, || true)
if [ -n "$csvs" ]; then
  echo; echo "== defaults and the strongest mitigations (means over frames) =="
  bash tools/bench/summary.sh "$csvs" "^(default|axes3-best|res-2048|res-4096${EXTRA_VARIANTS:+|${EXTRA_VARIANTS//,/|}})\$" short | tee "$out/summary.md"
  bash tools/bench/summary.sh "$csvs" > "$out/summary_full.md"
  if command -v gnuplot >/dev/null; then bash tools/bench/plot.sh "$csvs" "$out"; fi
fi
exit $status
