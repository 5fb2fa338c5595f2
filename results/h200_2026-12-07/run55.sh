#!/usr/bin/env bash
# Device run 55 (session 65): (1) the transfer-queue probe again with its `queue2` mode (the
# copy on a second queue of the main family, which needs no sharing across families), at
# stack-mating's copy (17 MB) and stack-touching's (6 MB); (2) three ways of making a kept
# result's new memory ready, one binary, s89x = eca493d plus
# experiments/session65_prepare_switches.diff (src/narrow/parallel.hpp, resizeFresh of two
# arrays: the two loops, and a switch for the other two orders; run 54's switches too):
#   two  (unset)            the responses' pages touched in a loop of their own, then their
#                           resize() as the first task of the loop that touches the pairs' pages
#   one  VKC_EXP_PREPARE=one  dc4d6ac: one loop, the resize() its first task (faulting the
#                           responses' pages on one thread)
#   old  VKC_EXP_PREPARE=old  before dc4d6ac: one loop over every page, then both resize()s
# `default` (detect() keeping every result), the six scenes with results over a megabyte,
# three rounds in rotating order. Run from the repository root with `.gl` and `build-pack`
# carried (build-pack/bins.tar.xz: build-carry/s89x/vkcollide_bench; build-pack/cgal.tar.xz;
# build-pack/tq_probe from experiments/session65_transfer_queue_probe.cpp). Analyse with
# `python3 analyse46.py modes run55 prep two` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run55; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run55.tgz run55; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
for p in "17 4000" "17 8000" "6 1500"; do set -- $p; timeout 60 build-pack/tq_probe $1 $2 25 > $W/tq-$1-$2.csv 2>&1; log tq-$1-$2 $?; done
BIN=build-carry/s89x/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
BIG=stack-mating,stack-touching,wall-touching,pile-deep,spheres-100x10K,cad-mating
prep() {  # $1: round, $2: two, one or old
  local e=""; [ $2 != two ] && e="VKC_EXP_PREPARE=$2"
  env $e timeout 60 $BIN $B --frames 10 --warmup-ms 300 --variants default --scenes $BIG \
    --csv $W/prep-$1-$2.csv --profile $W/prep-$1-$2_profile.csv > $W/prep-$1-$2.txt 2>&1; log prep-$1-$2 $?
}
prep a two; prep a old; prep a one; prep b one; prep b two; prep b old; prep c old; prep c one; prep c two
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run55.tgz run55
cat $W/log.txt; cat $W/gpu.txt; cat $W/tq-*.csv
