#!/usr/bin/env bash
# Device run 5 of 2026-12-06 (session 48, review): the rounding's midpoints made from c's bits
# and a direction (no double half gap), the exact GPU tests, device pairs and exact decision.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run5; mkdir -p $W
nvidia-smi --query-gpu=name,driver_version --format=csv > $W/gpu.txt 2>&1
for t in vkcollide_exact_gpu_tests vkcollide_device_pairs_tests vkcollide_exact_decision_tests; do
  timeout 90 build-carry/new/$t > $W/$t.txt 2>&1; echo "$t rc=$?" >> $W/log.txt
done
tar -C /tmp -czf $OUT/run5.tgz run5; cat $W/log.txt; for f in $W/*_tests.txt; do tail -n 2 $f; done
