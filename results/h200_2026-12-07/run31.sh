#!/usr/bin/env bash
# Device run 31 (session 57): the small decided-pair narrow phase on the calling thread.
# Run from the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s58/vkcollide_bench (78cea1d, main before) and
#                           build-carry/s59/vkcollide_bench (the change), Release, stripped
#   build-pack/cgal.tar.xz  data/cgal-run
# PART=1: small scenes (detect(), detectInto(), pipelined), s58 and s59 alternated (a: s58 first, b: s59 first), then every
# scene at s59 (detect() and detectInto()). PART=2: the small scenes again, alternated.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run31-${PART:-1}; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run31.tgz $(basename $W); }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
SMALL=bunnies-2x75K,deform-pair-100K,deform-armadillo-bunny,ball-cloth,ball-cloth-moving,mixed-gpu,mixed-gpu-b,twisted-bar,twisted-ribbon,drape-flap,drape-flap-b,deform-tori,deform-blobs,spheres-8x10K,bunnies-2x75K-deep,deform-pair-1M
timeout 60 build-carry/s59/vkcollide_bench $B --frames 6 --warmup-ms 1000 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
small() {  # $1: tag, $2: build
  timeout 150 build-carry/$2/vkcollide_bench $B --frames 10 --warmup-ms 300 --variants default,into,pipelined --scenes $SMALL \
    --csv $W/$1-$2.csv --profile $W/$1-$2_profile.csv > $W/$1-$2.txt 2>&1; log $1-$2 $?
}
small a s58; small a s59; small b s59; small b s58
if [ "${PART:-1}" = 1 ]; then
  timeout 200 build-carry/s59/vkcollide_bench $B --frames 8 --warmup-ms 600 --variants default,into --csv $W/all.csv \
    --profile $W/all_profile.csv > $W/all.txt 2>&1; log all $?
fi
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run31.tgz $(basename $W)
cat $W/log.txt
