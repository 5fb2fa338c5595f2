#!/usr/bin/env bash
# Device run 25 of 2026-12-06 (session 52): detect()'s host result when each frame's result is
# released before the next (the bench's `dropped` variant) against every frame's kept
# (`default`) and detectInto() (`into`); fresh memory when every allocation is kept; the API
# tests of the GPU-sorted host result (DetectStats::host.prepare_ms among them), device pairs
# and an engine's loop on NVIDIA.
#   build-carry/head/   the bench (with `dropped`) and the test executables at 0e6dd0f (Release)
#   build-carry/probe/  experiments/session52_memprobe.cpp with the kept mode (g++ -O2 -std=c++20 -pthread)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run25; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run25.tgz run25; }
nvidia-smi --query-gpu=name,driver_version --format=csv > $W/gpu.txt 2>&1
timeout 90 build-carry/probe/memprobe 16 > $W/memprobe16.txt 2>&1; log memprobe16 $?
B="--data data/cgal-run --cache /tmp/bc --set all --frames 6 --threads 16 --warmup-ms 1000"
timeout 60 build-carry/head/vkcollide_bench $B --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
for n in 1 2; do
  timeout 100 build-carry/head/vkcollide_bench $B --variants default,dropped,into --scenes stack-mating,stack-touching,wall-touching --csv $W/$n-head.csv --profile $W/$n-head_profile.csv > $W/$n-head.txt 2>&1; log $n-head $?
done
for t in exact_decision device_pairs engine_loop; do
  timeout 150 build-carry/head/vkcollide_${t}_tests > $W/$t.txt 2>&1; log $t $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run25.tgz run25
cat $W/log.txt; grep -hE "passed|failed" $W/*_tests.txt $W/exact_decision.txt $W/device_pairs.txt $W/engine_loop.txt 2>/dev/null; grep -E "kept|current" $W/memprobe16.txt; grep -hE "stack|wall" $W/*-head.txt
