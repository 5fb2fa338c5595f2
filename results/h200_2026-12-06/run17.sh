#!/usr/bin/env bash
# Device run 17 of 2026-12-06 (session 50): the tiled shallow sweep by object runs.
#   build-carry/ranked/  vkcollide_bench at f12968a (the tiled sweep: each cell ranked by
#                        (zlo, index), every later entry walked)
#   build-carry/new/     each cell ranked by (object, zlo, index), cut into one run per object;
#                        an entry walks only the runs of objects it may collide with (its own
#                        from the next position, another's from a binary search); bench and tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run17; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run17.tgz run17; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
timeout 90 build-carry/new/vkcollide_cells_tests > $W/cells.txt 2>&1; log cells $?
timeout 90 build-carry/new/vkcollide_device_pairs_tests > $W/device_pairs.txt 2>&1; log device_pairs $?
timeout 90 build-carry/new/vkcollide_engine_loop_tests > $W/engine_loop.txt 2>&1; log engine_loop $?
H=deep-blobs,deep-bunny-elephant,pile-shapes,spheres-60x10K-dense,bunnies-2x75K,stack-mating,stack-touching,pile-deep,wall-touching
n=0
for b in ranked new new ranked; do
  n=$((n + 1)); o=$n-$b
  V=device-only,default
  timeout 110 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants $V --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run17.tgz run17
cat $W/log.txt; grep -E "passed|failed" $W/cells.txt $W/device_pairs.txt $W/engine_loop.txt
