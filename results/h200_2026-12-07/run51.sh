#!/usr/bin/env bash
# Device run 51, prepared in session 63 and not yet run (the machines were refused six times,
# then lending paused). First a probe of how this host makes new memory ready
# (experiments/session63_memory_probe.cpp, built with `g++ -O2 -std=c++20 -pthread
# experiments/session63_memory_probe.cpp -o build-pack/probe`, carried in build-pack): 30 MB and 8 MB of fresh anonymous memory, touched one byte a page,
# memset, or populated with MADV_POPULATE_WRITE, with and without MADV_HUGEPAGE, on 16
# threads or one; then issue 27's kinds at s84 (= a5ff5c5, the one-write-a-page touch)
# under detect(), detectInto() and device-only results, in two rounds (the variants in
# opposite orders). Run from the
# repository root with `.gl` and `build-pack` carried (build-pack/bins.tar.xz:
# build-carry/s84/vkcollide_bench; build-pack/cgal.tar.xz: data/cgal-run). Analyse with
# `python3 analyse46.py kinds run51` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run51; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run51.tgz run51; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $W/host.txt 2>&1
nproc >> $W/host.txt; grep -m1 "model name" /proc/cpuinfo >> $W/host.txt; uname -r >> $W/host.txt
timeout 60 build-pack/probe 30 16 > $W/probe30.csv 2>&1; log probe30 $?
timeout 60 build-pack/probe 8 16 > $W/probe8.csv 2>&1; log probe8 $?
BIN=build-carry/s84/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-bar,twisted-ribbon,ball-cloth,drape-flap-b,stack-touching,wall-touching,spheres-60x10K,bunnies-2x75K-twin
for r in a b; do
  v=default,into,device-only; [ $r = b ] && v=device-only,into,default
  timeout 120 $BIN $B --frames 8 --warmup-ms 400 --variants $v --scenes $KINDS \
    --csv $W/kinds-$r.csv --profile $W/kinds-$r"_profile.csv" > $W/kinds-$r.txt 2>&1; log kinds-$r $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run51.tgz run51
cat $W/log.txt; cat $W/gpu.txt
