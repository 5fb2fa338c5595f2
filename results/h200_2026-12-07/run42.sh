#!/usr/bin/env bash
# Device run 42 (session 59): where a deforming mesh's updateVertices goes at the small scenes'
# sizes (25K and 64K vertices: deform-pair-100K's and deform-armadillo-bunny's meshes), and at
# 1M for comparison with results/h200_2026-11-25f: vkcollide_bench_frames' update rows (no
# detection). Run from the repository root with `.gl` and `build-pack` carried
# (build-carry/s70: a8c27fc's vkcollide_bench_frames, Release, stripped).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run42; mkdir -p $W
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
for v in 25000 65536 1000000; do
  timeout 60 build-carry/s70/vkcollide_bench_frames --vertices $v --methods none --frames 60 --threads 16 > $W/update_$v.csv 2> $W/update_$v.err
  echo "vertices $v rc=$?" >> $W/log.txt
done
tar -C /tmp -czf $OUT/run42.tgz run42
cat $W/log.txt
