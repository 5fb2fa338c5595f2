#!/usr/bin/env bash
# Device run 10 of 2026-12-06 (session 49): the cell of each entry written by the scan.
#   build-carry/base/            vkcollide_bench at f13377a (the setup's records staged; run 9's "staged")
#   build-carry/fill-skipcells/  an experiment: base with the fill storing an entry's cell only
#                                where the buffer does not hold it already (a rigid scene's
#                                later frames: each slot keeps its cell), the fill without that store
#   build-carry/new/             the scan's last step writes every entry's cell in entry order,
#                                the fill no longer does; its bench and tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run10; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run10.tgz run10; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
timeout 90 build-carry/new/vkcollide_cells_tests > $W/cells.txt 2>&1; log cells $?
timeout 90 build-carry/new/vkcollide_device_pairs_tests > $W/device_pairs.txt 2>&1; log device_pairs $?
H=deep-blobs,deep-bunny-elephant,pile-shapes,spheres-60x10K-dense,bunnies-2x75K,stack-mating
n=0
for b in base fill-skipcells new new base; do
  n=$((n + 1)); o=$n-$b
  timeout 90 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants device-only,default --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run10.tgz run10
cat $W/log.txt; grep -E "passed|failed" $W/cells.txt $W/device_pairs.txt
