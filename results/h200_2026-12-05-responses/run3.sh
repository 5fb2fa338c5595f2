#!/usr/bin/env bash
# Device run 3 of 2026-12-05 (session 46): the tests of runs 1 and 2 again after the
# quotient's and root's start got one Newton step from its exact residual (runs 1 and 2:
# NVIDIA's own double division and square root were off by up to some 70 ulps, and one-ulp
# steps from 5 ulps beyond that ran out of their 64); the rounding test now steps from the
# CPU's value 5 ulps off and prints how far the driver's own were.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry/new; W=/tmp/run3; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run3.tgz run3; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
t() {  # executable, output name, test spec (none: every test)
  timeout 120 $B/$1 ${3:+"$3"} > $W/$2.txt 2>&1; log $2 $?
}
t vkcollide_exact_gpu_tests exact_gpu ""
t vkcollide_device_pairs_tests device_pairs ""
t vkcollide_exact_decision_tests pair_sort "pair sort*"
t vkcollide_engine_loop_tests engine_loop ""
t vkcollide_stability_tests partners "reliable: a triangle with 5\,000 partners*"
cat $W/log.txt; grep "rounding:" $W/exact_gpu.txt
