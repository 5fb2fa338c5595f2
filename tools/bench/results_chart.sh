#!/usr/bin/env bash
# docs/results.md's speed-accuracy chart and the before/after table of the reliable method, from
# the H200 CSVs in results/:
#   tools/bench/results_chart.sh [OUT.png]     (default docs/frontier.png; the table goes to stdout)
# Series: the 2026-11-25 afternoon run (h200_2026-11-25b: tuning.csv, held-out.csv, warm clocks; default = the reliable method, peeling,
# paper-sep), the defaults before the reliable method (before_old_defaults.csv, measured with the earlier
# build), and the 2026-11-22 resolution sweep of the paper's method on the same kind of machine
# (h200_vkcollide_small.csv 256-4096, h200_vkcollide_large.csv 512-2048: single peeling, compute
# sampling; the mitigation variants axes3/best were never run on the H200, so none are drawn).
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-docs/frontier.png}"
run="${RUN:-results/h200_2026-11-25b}"  # RUN=folder: another run with tuning.csv and held-out.csv
before=results/h200_2026-11-25/before_old_defaults.csv
bash tools/bench/frontier.sh \
  --title "NVIDIA H200: crossing-pair recall against end-to-end ms per frame, per scene kind (means of frames >= 1)" \
  --link before:default \
  --legend "before=defaults before the reliable method (earlier build)" \
  --legend "nov22=peeling at 256²-4096² (2026-11-22 build)" \
  --legend "link=grey line: one scene, defaults before to reliable" \
  "$out" "$run/tuning.csv" "$run/held-out.csv" "$before@before" \
  "results/h200_2026-11-22/h200_vkcollide_small.csv@nov22@^single-compute\$" "results/h200_2026-11-22/h200_vkcollide_large.csv@nov22@^single-compute\$" >&2
bash tools/bench/before_after.sh "$before" "$run/tuning.csv,$run/held-out.csv"
