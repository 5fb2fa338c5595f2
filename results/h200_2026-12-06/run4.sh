#!/usr/bin/env bash
# Device run 4 of 2026-12-06 (session 48): the rounding's one-ulp tests in 64-bit integers
# (run 3 showed NVIDIA's compiled double-arithmetic side tests losing the product's error
# term, though TwoProduct alone was exact). The exact GPU tests, the device responses (device
# pairs, exact decision), then the bench of the same build for the responses pass's time.
#   build-carry/new/  the tests and vkcollide_bench with the integer side tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run4; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run4.tgz run4; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
t() {  # executable, output name
  timeout 90 build-carry/new/$1 > $W/$2.txt 2>&1; log $2 $?
}
t vkcollide_exact_gpu_tests exact_gpu
t vkcollide_device_pairs_tests device_pairs
t vkcollide_exact_decision_tests exact_decision
timeout 80 build-carry/new/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants default --scenes stack-mating,stack-touching,pile-shapes,bunnies-2x75K \
  --frames 6 --threads 16 --warmup-ms 1000 --csv $W/new.csv --profile $W/new_profile.csv > $W/new.txt 2>&1; log bench $?
gzip $W/*_profile.csv; tar -C /tmp -czf $OUT/run4.tgz run4
cat $W/log.txt; grep -E "rounding|FAILED|differ|passed|failed" $W/exact_gpu.txt | head -20; tail -3 $W/device_pairs.txt $W/exact_decision.txt
