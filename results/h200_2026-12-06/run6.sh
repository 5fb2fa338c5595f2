#!/usr/bin/env bash
# Device run 6 of 2026-12-06 (session 49).
#   build-carry/base/  vkcollide_bench at 2e945b3 (the session's start)
#   build-carry/new/   footprints counted and filled with one atomic per distinct cell of a
#                      subgroup (cells_setup, cells_fill), the fit's bounds reduced per
#                      workgroup; its bench and tests
# First the cell tests on NVIDIA (the subgroup aggregation under independent thread
# scheduling), then both benches, device-only and default, two rounds in opposite orders.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run6; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run6.tgz run6; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
t() {  # executable, output name
  timeout 90 build-carry/new/$1 > $W/$2.txt 2>&1; log $2 $?
}
t vkcollide_cells_tests cells
t vkcollide_device_pairs_tests device_pairs
t vkcollide_engine_loop_tests engine_loop
bench() {  # build, variants, output name
  timeout 100 build-carry/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants $2 --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$3.csv --profile $W/$3_profile.csv > $W/$3.txt 2>&1; log $3 $?
}
H=deep-blobs,deep-bunny-elephant,pile-shapes,spheres-60x10K-dense,bunnies-2x75K,stack-mating
bench base device-only,default base_a
bench new device-only,default new_a
bench new default,device-only new_b
bench base default,device-only base_b
gzip $W/*_profile.csv; tar -C /tmp -czf $OUT/run6.tgz run6
cat $W/log.txt; grep -E "passed|failed|FAILED" $W/cells.txt $W/device_pairs.txt $W/engine_loop.txt | head
