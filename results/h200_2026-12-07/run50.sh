#!/usr/bin/env bash
# Device run 50 (session 63): result memory made ready by one write per 4 KiB page instead of
# a memset over every byte (src/narrow/parallel.hpp, fresh::Plan::touch). One binary, s82x =
# the change plus experiments/session63_memset_touch.diff, runs both: VKC_EXP_MEMSET_TOUCH=1
# is the old memset. Every bench scene under `default` (detect() keeping every result) in
# four rounds, the two policies in alternating order (a: stride memset, b: memset stride, c,
# d likewise); then the scenes with results over a megabyte under detect(), detectInto() and
# dropped results, both policies; then issue 27's kinds under the change. Run from the
# repository root with `.gl` and `build-pack` carried (build-pack/bins.tar.xz:
# build-carry/s82x/vkcollide_bench, Release, stripped; build-pack/cgal.tar.xz: data/cgal-run).
# Analyse with `python3 analyse46.py paired run50` and `python3 analyse46.py kinds run50`
# from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run50; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run50.tgz run50; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $W/host.txt 2>&1
nproc >> $W/host.txt; grep -m1 "model name" /proc/cpuinfo >> $W/host.txt
BIN=build-carry/s82x/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
sweep() {  # $1: round, $2: new (one write a page) or old (memset)
  local e=""; [ $2 = old ] && e="VKC_EXP_MEMSET_TOUCH=1"
  env $e timeout 150 $BIN $B --frames 6 --warmup-ms 400 --variants default --csv $W/sweep-$1-$2.csv \
    --profile $W/sweep-$1-$2_profile.csv > $W/sweep-$1-$2.txt 2>&1; log sweep-$1-$2 $?
}
sweep a new; sweep a old; sweep b old; sweep b new; sweep c new; sweep c old; sweep d old; sweep d new
BIG=stack-mating,stack-touching,wall-touching,pile-deep,spheres-100x10K,cad-mating
big() {
  local e=""; [ $2 = old ] && e="VKC_EXP_MEMSET_TOUCH=1"
  env $e timeout 120 $BIN $B --frames 8 --warmup-ms 400 --variants default,into,dropped --scenes $BIG \
    --csv $W/big-$1-$2.csv --profile $W/big-$1-$2_profile.csv > $W/big-$1-$2.txt 2>&1; log big-$1-$2 $?
}
big a new; big a old; big b old; big b new
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-bar,twisted-ribbon,ball-cloth,drape-flap-b,stack-touching,wall-touching,spheres-60x10K,bunnies-2x75K-twin
timeout 200 $BIN $B --frames 8 --warmup-ms 400 --variants default,into,device-only,pipelined \
  --scenes $KINDS --csv $W/kinds.csv --profile $W/kinds_profile.csv > $W/kinds.txt 2>&1; log kinds $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run50.tgz run50
cat $W/log.txt
