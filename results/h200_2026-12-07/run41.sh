#!/usr/bin/env bash
# Device run 41 (session 59): the deforming scenes' command buffer reuse, s69 (f942633) against
# s70 (the clear and scan over the most cells of the last 32 runs within the band). Run from the
# repository root with `.gl` and `build-pack` carried (build-carry/s69 and s70, vkcollide_bench,
# Release, stripped; data/cgal-run). Rounds a (s69 first) and b (s70 first).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run41; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run41.tgz run41; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
SCENES=deform-blobs,deform-armadillo-bunny,deform-tori,deform-pair-100K,bunnies-2x75K
one() {  # $1: round, $2: build
  timeout 100 build-carry/$2/vkcollide_bench $B --frames 10 --warmup-ms 600 --variants default,into --scenes $SCENES \
    --csv $W/$1-$2.csv --profile $W/$1-$2_profile.csv > $W/$1-$2.txt 2>&1; log $1-$2 $?
}
one a s69; one a s70; one b s70; one b s69
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run41.tgz run41
cat $W/log.txt
