#!/usr/bin/env bash
# Two builds of vkcollide_bench_narrow on the pair path, from the few hundred pairs the
# reliable method sends every detection to a million (docs/narrow_phase.md, "Small pair
# counts"), one table: the median ms of each stage, before -> after, per workload and
# thread count. Then, when AFTER has them, its probes: the pair path's front in both forms
# (where the switch narrow::kSerialPairsBelow belongs on this host) and how fast a
# sleeping pool's workers join a loop.
#
#   bash tools/bench/bench_narrow_compare.sh BEFORE_BINARY AFTER_BINARY [threads, default 1,16]
#
# Workloads (input pairs): graze 100K hits (~500, like deform-pair-100K's ~650), graze 1M
# hits (~1,600), spheres 1M hits (~3,700), graze 1M boxes (~7,700), spheres 1M boxes
# (~20K), pile hits (~35K), deep 1.2M near boxes (~87K, self-collision off) and (~1.7M,
# on). "hits" sends only the intersecting pairs, as the GPU pair stage does; "boxes" every
# box-overlapping pair (more tests per pair). 1 ms between calls, so the pool's workers
# are asleep when a call starts, as after a GPU wait. Both binaries must know --pairs-sent
# and --gap-us (bench_narrow.cpp from commit d493674 on). About 3 minutes on 16 threads.
set -euo pipefail
before=$1 after=$2 threads=${3:-1,16}
common=(--paths pairs --threads "$threads" --gap-us 1000)
workloads=(
  "--pairs-sent hits --self off --modes contact --scenes graze --sizes 100000,1000000 --repeat 31"
  "--pairs-sent hits --self off --modes contact --scenes spheres --sizes 1000000 --repeat 31"
  "--pairs-sent boxes --self off --modes contact --scenes graze,spheres --sizes 1000000 --repeat 31"
  "--pairs-sent hits --self off --modes contact --scenes pile --repeat 15"
  "--pairs-sent boxes --self off,on --modes near --scenes deep --sizes 1200000 --repeat 7"
)
tmp=$(mktemp -d)
trap 'rm -r "$tmp"' EXIT
for w in "${workloads[@]}"; do
  # shellcheck disable=SC2086  # $w is a list of arguments
  "$before" "${common[@]}" $w --csv "$tmp/part.csv" >/dev/null && tail -n +2 "$tmp/part.csv" >> "$tmp/before.csv"
  # shellcheck disable=SC2086
  "$after" "${common[@]}" $w --csv "$tmp/part.csv" >/dev/null && tail -n +2 "$tmp/part.csv" >> "$tmp/after.csv"
done
echo "host: $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
# CSV columns: 1 scene, 3 self, 5 triangles, 6 inputs, 7 threads, 14 positive tests, 16 validate,
# 17 gather, 18 sweep (pairing up), 20 test, 21 sort, 22 response, 23 total, 24 fastest total,
# 25 process CPU.
awk -F, 'NR == FNR { b[$1 "," $3 "," $5 "," $6 "," $7] = $0; next }
FNR == 1 { printf "%-8s %-4s %8s %8s %4s %7s | %-12s %-12s %-12s %-12s %-12s %-12s %-14s %-12s %-12s\n", "scene", "self", "tris",
           "inputs", "thr", "hits", "validate", "gather", "pair up", "test", "sort", "response", "total", "| total min", "cpu" }
{ split(b[$1 "," $3 "," $5 "," $6 "," $7], o, ",")
  printf "%-8s %-4s %8s %8s %4s %7s |", $1, $3, $5, $6, $7, $14
  for (c = 16; c <= 25; ++c) if (c != 19) printf "%s %5.3f->%5.3f", c == 24 ? " |" : "", o[c], $c
  printf "\n" }' "$tmp/before.csv" "$tmp/after.csv"
if "$after" --wake-probe --threads 1 --repeat 1 >/dev/null 2>&1; then
  echo
  echo "front of the pair path, serial vs parallel form (median ms; kSerialPairsBelow = 8192 in this build):"
  "$after" --front-probe --paths pairs --threads "$threads" --gap-us 1000 --repeat 31 --pairs-sent hits --self off --modes contact \
    --scenes graze,spheres --sizes 100000,1000000
  "$after" --front-probe --paths pairs --threads "$threads" --gap-us 1000 --repeat 31 --pairs-sent boxes --self off --modes contact \
    --scenes graze,spheres --sizes 100000,1000000 | tail -n +2
  "$after" --front-probe --paths pairs --threads "$threads" --gap-us 1000 --repeat 9 --pairs-sent boxes --self off --modes near \
    --scenes deep --sizes 1200000 | tail -n +2
  echo
  echo "pool wake-up (us from the call until the first / middle / last worker joins a loop):"
  "$after" --wake-probe --threads "${threads##*,}" --repeat 21
fi
