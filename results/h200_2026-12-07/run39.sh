#!/usr/bin/env bash
# Device run 39 (session 59): s66 (66811c2, the early pairs in pieces) against s68 (the naming
# during the GPU only from 32,768 pairs in the last detection, 9a2f96b; a result's responses
# zeroed beside the pairs' page touching after their own pages were touched in parallel).
# Run from the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s66 (66811c2) and build-carry/s68 (0e5d6a7),
#                           vkcollide_bench, Release, stripped
#   build-pack/cgal.tar.xz  data/cgal-run
# Rounds a and c (s66 first) and b (s68 first) on the scenes with many pairs, detect() with the
# results kept (default) and dropped, and detectInto(); then every scene at s68 (detect() and detectInto()).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run39; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run39.tgz run39; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s68/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
SCENES=stack-mating,stack-touching,wall-touching,cad-mating,pile-deep,spheres-60x10K-dense,pile-shapes
one() {  # $1: round, $2: build
  timeout 120 build-carry/$2/vkcollide_bench $B --frames 7 --warmup-ms 200 --variants default,dropped,into --scenes $SCENES \
    --csv $W/$1-$2.csv --profile $W/$1-$2_profile.csv > $W/$1-$2.txt 2>&1; log $1-$2 $?
}
one a s66; one a s68; one b s68; one b s66; one c s66; one c s68
timeout 200 build-carry/s68/vkcollide_bench $B --frames 8 --warmup-ms 600 --variants default,into --csv $W/all.csv \
  --profile $W/all_profile.csv > $W/all.txt 2>&1; log all $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run39.tgz run39
cat $W/log.txt
