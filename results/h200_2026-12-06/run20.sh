#!/usr/bin/env bash
# Device run 20 of 2026-12-06 (session 50): the tiles' walks over entries stored in sorted order.
#   build-carry/base/  vkcollide_bench at 4a46521 (the tiled sweep: the ranking writes each
#                      entry's tile position at its sorted one; the walks follow it)
#   build-carry/new/   the ranking writes the entry itself and its zlo at its sorted position;
#                      the walks read them in place; its bench and cell tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run20; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run20.tgz run20; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
T=build-carry/new/vkcollide_cells_tests
timeout 30 $T "cells: the shallow sweep's tiles hold cells across chunk boundaries\, deep cells and depth ties" > $W/cells_tiles.txt 2>&1; log cells_tiles $?
timeout 30 $T "cells: two overlapping spheres\, every pair at every resolution" > $W/cells_spheres.txt 2>&1; log cells_spheres $?
H=deep-blobs,pile-shapes,pile-deep,spheres-60x10K-dense,stack-mating,wall-touching,bunnies-2x75K
n=0
for b in base new new base; do
  n=$((n + 1)); o=$n-$b
  timeout 60 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants device-only --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run20.tgz run20
cat $W/log.txt; grep -E "passed|failed" $W/cells_*.txt
