#!/usr/bin/env bash
# Device run 9 of 2026-12-06 (session 49): the setup pass's records written through shared memory.
#   build-carry/new/               the fit's bounds reduced per workgroup (runs 7 and 8's "new")
#   build-carry/setup-skipwrites/  an experiment: HEAD's setup storing a record only where it
#                                  differs from what the buffer holds (in a rigid scene's later
#                                  frames: no stores), the time of the pass without its writes
#   build-carry/staged/            new with the setup's records copied out of shared memory as
#                                  consecutive 16-byte words; its bench and tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run9; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run9.tgz run9; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
timeout 90 build-carry/staged/vkcollide_cells_tests > $W/cells.txt 2>&1; log cells $?
timeout 90 build-carry/staged/vkcollide_device_pairs_tests > $W/device_pairs.txt 2>&1; log device_pairs $?
H=deep-blobs,deep-bunny-elephant,pile-shapes,spheres-60x10K-dense,bunnies-2x75K,stack-mating
n=0
for b in new setup-skipwrites staged staged new; do
  n=$((n + 1)); o=$n-$b
  x=""; [ $n = 3 ] && x="--pipeline-stats $W/pipeline_stats.csv"
  timeout 90 build-carry/$b/vkcollide_bench $x --data data/cgal --cache /tmp/bc --set all --variants device-only,default --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run9.tgz run9
cat $W/log.txt; grep -E "passed|failed" $W/cells.txt $W/device_pairs.txt; grep -E "cells-setup|cells-fill" $W/pipeline_stats.csv
