#!/usr/bin/env bash
# Device run 36 (session 59): run 35 again, the milestone now looked for at the GPU time
# the last submission's timestamps put it (s65 = 9af9fce; run 35's s64 looked for it where
# it was seen last, which stayed late after a frame in the H100's slow clock state). Run from the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s63 (51a926d, before) and build-carry/s65 (9af9fce: the pairs named while the GPU computes the responses),
#                           vkcollide_bench, Release, stripped
#   build-pack/cgal.tar.xz  data/cgal-run
# Rounds a (s63 first) and b (s65 first) on the scenes with many pairs, detect() with the
# results kept (default) and dropped, and detectInto(); then every scene at s65 (detect() and detectInto()).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run36; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run36.tgz run36; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s65/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
SCENES=stack-mating,stack-touching,wall-touching,cad-mating,pile-deep,spheres-60x10K-dense,pile-shapes
one() {  # $1: round, $2: build
  timeout 120 build-carry/$2/vkcollide_bench $B --frames 7 --warmup-ms 200 --variants default,dropped,into --scenes $SCENES \
    --csv $W/$1-$2.csv --profile $W/$1-$2_profile.csv > $W/$1-$2.txt 2>&1; log $1-$2 $?
}
one a s63; one a s65; one b s65; one b s63
timeout 200 build-carry/s65/vkcollide_bench $B --frames 8 --warmup-ms 600 --variants default,into --csv $W/all.csv \
  --profile $W/all_profile.csv > $W/all.txt 2>&1; log all $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run36.tgz run36
cat $W/log.txt
