#!/usr/bin/env bash
# Device run 53 (session 64): the responses' one-thread resize() run as the first task of the
# loop that touches the pairs' new pages, instead of after it (src/narrow/parallel.hpp,
# resizeFresh of two arrays). One binary, s86x = the change plus
# experiments/session64_old_prepare.diff (VKC_EXP_OLD_PREPARE=1: the old order), Release,
# stripped. The scenes whose results pass a megabyte under `default` (detect() keeping every
# result: the path that prepares new memory), four rounds, the two orders alternating (a: new
# old, b: old new, c, d likewise). Run from the repository root with `.gl` and `build-pack`
# carried (build-pack/bins.tar.xz: build-carry/s86x/vkcollide_bench; build-pack/cgal.tar.xz:
# data/cgal-run). Analyse with `python3 analyse46.py order run53` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run53; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run53.tgz run53; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
BIN=build-carry/s86x/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
BIG=stack-mating,stack-touching,wall-touching,pile-deep,spheres-100x10K,cad-mating
order() {  # $1: round, $2: new or old
  local e=""; [ $2 = old ] && e="VKC_EXP_OLD_PREPARE=1"
  env $e timeout 60 $BIN $B --frames 10 --warmup-ms 300 --variants default --scenes $BIG \
    --csv $W/order-$1-$2.csv --profile $W/order-$1-$2_profile.csv > $W/order-$1-$2.txt 2>&1; log order-$1-$2 $?
}
order a new; order a old; order b old; order b new; order c new; order c old; order d old; order d new
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run53.tgz run53
cat $W/log.txt; cat $W/gpu.txt
