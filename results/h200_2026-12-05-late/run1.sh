#!/usr/bin/env bash
# H200 run 1 of 2026-12-05 (late session). Three builds of the bench programs:
#   build-carry/base/   b287d8b (the session's start)
#   build-carry/vcell/  03d6e6f: the setup stores the CPU's world vertices once per triangle
#                       (5a14ad1), the proximity sweep takes neighbours in their vertex cell
#   build-carry/        6dd498a: and CellsTriangle / CellsGeometry padded to 16-byte words
#                       (this build's CLI and test executables too)
#   build-carry/wg/     6dd498a + 0f9ee16 (branch wg-counters; landed as 2607f87, reverted in 444da6b): the pair and proximity
#                       passes' header counters summed per workgroup in shared memory
#   build-carry/nocount/ an experiment, never committed: 6dd498a with subgroupCount and
#                       subgroupCount64 (the header's statistics counters) compiled empty,
#                       to see what the counters' same-address atomics cost
# Proximity (each build but vcell), the tuning set (base: default, grid-tuned; new, wg:
# default), the held-out set (base, new: default). (Cut to fit what device time was left
# after a dozen failed starts: no piles, no tests.)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz  # build-carry/, packed (the carried files are limited to 64 MiB)
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; S=/tmp/scenes; W=/tmp/run1; mkdir -p $W
start=$(date +%s)
# After every step the folder is packed into $OUT again (one file: at most 8 come back), so
# a timeout still returns what ran.
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run1.tgz run1; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
prox() {  # build folder, output name
  timeout 100 $1/vkcollide_bench_proximity --scenes pair,cloth-391k,cloth-524k --factors 0.1,0.5 \
      --frames 10 --warmup-ms 1500 --threads 16 --passes --reference --csv $W/$2.csv > $W/$2.txt 2>&1; log $2 $?
}
bench() {  # build folder, set, variants, output name
  timeout 200 $1/vkcollide_bench --data data/cgal --cache /tmp/bc --set $2 --variants $3 --frames 6 --threads 16 \
      --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
prox $B/base base_proximity
prox $B new_proximity
prox $B/wg wg_proximity
prox $B/nocount nocount_proximity
bench $B/base tuning default,grid-tuned base_tuning
bench $B tuning default new_tuning
bench $B/wg tuning default wg_tuning
bench $B/base held-out default base_held-out
bench $B held-out default new_held-out
cat $W/log.txt
