#!/usr/bin/env bash
# Device run 1 of 2026-12-06 (session 47).
#   build-carry/base/  vkcollide_bench at 5cb2e51 (the session's start)
#   build-carry/new/   the sweep's first four partners kept in registers (the second scan
#                      starts after the fourth), and detect() leaving the reliable method's
#                      submission in flight so that the result's memory is made ready while
#                      the GPU works; compiler statistics (--pipeline-stats); its bench
#                      and the test executables (52c7163: also the sorted pairs copied as they are checked)
# First the tests on NVIDIA (the rounding's Newton start that run 3 of 2026-12-05 never
# confirmed, device pairs and responses, the sweep through every cell test), then both
# benches, default and device-only, two rounds in opposite orders.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run1; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run1.tgz run1; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
t() {  # executable, output name, test spec (none: every test)
  timeout 60 build-carry/new/$1 ${3:+"$3"} > $W/$2.txt 2>&1; log $2 $?
}
t vkcollide_exact_gpu_tests exact_gpu ""
t vkcollide_device_pairs_tests device_pairs ""
t vkcollide_exact_decision_tests exact_decision ""
t vkcollide_engine_loop_tests engine_loop ""
t vkcollide_cells_tests cells ""
t vkcollide_stability_tests partners "reliable: a triangle with 5\,000 partners*"
t vkcollide_engine_gpu_tests statistics "pipeline statistics*"
bench() {  # build, variants, output name, more options
  timeout 80 build-carry/$1/vkcollide_bench $4 --data data/cgal --cache /tmp/bc --set all --variants $2 --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$3.csv --profile $W/$3_profile.csv > $W/$3.txt 2>&1; log $3 $?
}
H=stack-mating,stack-touching,pile-shapes,deep-blobs,bunnies-2x75K
bench base default,device-only base_a
bench new default,device-only new_a "--pipeline-stats $W/pipeline_stats.csv"
bench new device-only,default new_b
bench base device-only,default base_b
gzip $W/*_profile.csv; tar -C /tmp -czf $OUT/run1.tgz run1
cat $W/log.txt; grep -i "rounding\|driver" $W/exact_gpu.txt | head -20
