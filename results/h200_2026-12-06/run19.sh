#!/usr/bin/env bash
# Device run 19 of 2026-12-06 (session 50): the pair and exact passes' counters, two to an atomic.
#   build-carry/base/  vkcollide_bench at 4a46521 (the tiled sweep)
#   build-carry/new/   the pair pass adds duplicates and filtered, and (inline) exact tests and
#                      exact neighbours, the exact pass its tests and neighbours, each two with
#                      one 64-bit atomic per subgroup; its bench and tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run19; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run19.tgz run19; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
timeout 60 build-carry/new/vkcollide_device_pairs_tests > $W/device_pairs.txt 2>&1; log device_pairs $?
timeout 60 build-carry/new/vkcollide_cells_tests "cells: the exact pass follows the last run's canonical candidates" > $W/cells_exact.txt 2>&1; log cells_exact $?
timeout 60 build-carry/new/vkcollide_cells_tests "cells: the pair pass in chunks decides what one pass decides" > $W/cells_chunks.txt 2>&1; log cells_chunks $?
H=stack-mating,stack-touching,wall-touching,pile-shapes,pile-deep,spheres-60x10K-dense,deep-blobs
n=0
for b in base new new base; do
  n=$((n + 1)); o=$n-$b
  timeout 60 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants device-only --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run19.tgz run19
cat $W/log.txt; grep -E "passed|failed" $W/device_pairs.txt $W/cells_exact.txt $W/cells_chunks.txt
