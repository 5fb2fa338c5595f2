#!/usr/bin/env bash
# Device run 32 (session 57): the cell stage's clear and scan over every cell its buffers
# hold (within 4x the run's), so that deforming scenes keep their command buffer. Run from
# the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s59/vkcollide_bench (06ff50c) and
#                           build-carry/s60/vkcollide_bench (the change), Release, stripped
#   build-pack/cgal.tar.xz  data/cgal-run
# Rounds a (s59 first) and b (s60 first) on deforming scenes and on rigid scenes whose grid
# tuner may leave larger buffers than the grid it settles on.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run32; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run32.tgz run32; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
SCENES=deform-tori,deform-blobs,deform-armadillo-bunny,deform-pair-100K,deform-pair-1M,deep-blobs,bunnies-14x75K,stack-mating
timeout 60 build-carry/s60/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
one() {  # $1: round, $2: build
  timeout 60 build-carry/$2/vkcollide_bench $B --frames 8 --warmup-ms 200 --variants default,into --scenes $SCENES \
    --csv $W/$1-$2.csv --profile $W/$1-$2_profile.csv > $W/$1-$2.txt 2>&1; log $1-$2 $?
}
one a s59; one a s60; one b s60; one b s59
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run32.tgz run32
cat $W/log.txt
