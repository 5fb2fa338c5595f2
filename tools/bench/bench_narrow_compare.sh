#!/usr/bin/env bash
# Two builds of vkcollide_bench_narrow on the pair path at the pair counts the reliable
# method sends every detection (docs/narrow_phase.md, "Small pair counts"), one table:
# the median ms of each stage, before -> after, per scene, size and thread count.
#
#   bash tools/bench/bench_narrow_compare.sh BEFORE_BINARY AFTER_BINARY [threads, default 1,16]
#
# Workloads: graze (~500 / ~1,500 intersecting pairs of 100K / 1M triangles, like
# deform-pair-100K's ~650), spheres (~1,000 / ~3,300), pile (60 meshes, ~32K pairs); only
# the intersecting pairs are sent, as the GPU pair stage does; 1 ms between calls, so the
# pool's workers are asleep when a call starts, as after a GPU wait. Both binaries must
# know --pairs-sent and --gap-us (bench_narrow.cpp from commit d493674 on).
set -euo pipefail
before=$1 after=$2 threads=${3:-1,16}
args=(--paths pairs --pairs-sent hits --self off --modes contact --scenes graze,spheres,pile --sizes 100000,1000000
      --threads "$threads" --repeat 31 --gap-us 1000)
tmp=$(mktemp -d)
"$before" "${args[@]}" --csv "$tmp/before.csv" >/dev/null
"$after" "${args[@]}" --csv "$tmp/after.csv" >/dev/null
echo "host: $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
# CSV columns: 1 scene, 5 triangles, 7 threads, 14 positive tests, 16 validate, 17 gather,
# 20 test, 21 sort, 22 response, 23 total, 24 fastest total, 25 process CPU.
awk -F, 'NR == FNR { if (FNR > 1) b[$1 "," $5 "," $7] = $0; next }
FNR == 1 { printf "%-8s %8s %4s %6s | %-12s %-12s %-12s %-12s %-12s %-14s %-12s %-12s\n", "scene", "tris", "thr", "pairs",
           "validate", "gather", "test", "sort", "response", "total", "| total min", "cpu"; next }
{ split(b[$1 "," $5 "," $7], o, ",")
  printf "%-8s %8s %4s %6s |", $1, $5, $7, $14
  for (c = 16; c <= 25; ++c) if (c != 18 && c != 19) printf "%s %5.3f->%5.3f", c == 24 ? " |" : "", o[c], $c
  printf "\n" }' "$tmp/before.csv" "$tmp/after.csv"
rm -r "$tmp"
