#!/usr/bin/env bash
# Device run 33 (session 58). Run from the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s59 (06ff50c), s60 (9ea0099: the cell stage's clear and
#                           scan over every cell its buffers hold), s61 (the pairs' copy to the
#                           host beside the responses; with VKC_EXPERIMENT_TOP_STAMPS set, an
#                           uncommitted experiment: every pass timestamp but the last written at
#                           TOP_OF_PIPE, so no BOTTOM_OF_PIPE stamp waits between passes),
#                           s62 (s61 and the host's naming of sorted pairs by streaming stores),
#                           vkcollide_bench, Release, stripped; build-carry/mb/fresh (a
#                           microbenchmark of a fresh result vector: page touch vs resize) and build-carry/mb/name (the host naming of sorted pairs: plain vs streaming stores); both sources in experiments/
#   build-pack/cgal.tar.xz  data/cgal-run
# PART=1: run 32's rounds (s59 vs s60 on deforming scenes and three rigid ones).
# PART=2: s60, s61, s61 with top stamps and s62 on the scenes with many sorted pairs, alternated
#         (a, b), detect() kept, detect() dropped, detectInto(); then the microbenchmark.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run33-${PART:-1}; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run33.tgz $(basename $W); }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s60/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
if [ "${PART:-1}" = 1 ]; then
  SCENES=deform-tori,deform-blobs,deform-armadillo-bunny,deform-pair-100K,deform-pair-1M,deep-blobs,bunnies-14x75K,stack-mating
  one() {  # $1: round, $2: build
    timeout 100 build-carry/$2/vkcollide_bench $B --frames 8 --warmup-ms 200 --variants default,into --scenes $SCENES \
      --csv $W/$1-$2.csv --profile $W/$1-$2_profile.csv > $W/$1-$2.txt 2>&1; log $1-$2 $?
  }
  one a s59; one a s60; one b s60; one b s59
else
  SCENES=stack-mating,stack-touching,wall-touching,pile-shapes,bunnies-2x75K
  (cat /sys/kernel/mm/transparent_hugepage/enabled; lscpu | head -20; build-carry/mb/fresh; build-carry/mb/fresh x; build-carry/mb/name; build-carry/mb/name) > $W/fresh.txt 2>&1; log fresh $?
  one() {  # $1: round, $2: build, $3: tag
    timeout 100 build-carry/$2/vkcollide_bench $B --frames 7 --warmup-ms 200 --variants default,dropped,into --scenes $SCENES \
      --csv $W/$1-$3.csv --profile $W/$1-$3_profile.csv > $W/$1-$3.txt 2>&1; log $1-$3 $?
  }
  one a s60 s60; one a s61 s61; VKC_EXPERIMENT_TOP_STAMPS=1 one a s61 s61top; one a s62 s62
  one b s62 s62; VKC_EXPERIMENT_TOP_STAMPS=1 one b s61 s61top; one b s61 s61; one b s60 s60
fi
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run33.tgz $(basename $W)
cat $W/log.txt
