#!/usr/bin/env bash
# Device run 51, prepared in session 63 (not run then: no machine lent) and extended in session
# 64 before it ran. First a probe of how this host makes new memory ready
# (experiments/session63_memory_probe.cpp, built with `g++ -O2 -std=c++20 -pthread
# experiments/session63_memory_probe.cpp -o build-pack/probe`, carried in build-pack): 30 MB and
# 8 MB of fresh anonymous memory, touched one byte a page, memset, or populated with
# MADV_POPULATE_WRITE, with and without MADV_HUGEPAGE, on 16 threads or one, each followed by a
# one-thread memset over it. Then one binary, s85x = de736c8 plus
# experiments/session64_touch_modes.diff (VKC_EXP_TOUCH: 0 the committed one write a page after
# MADV_HUGEPAGE, 1 MADV_POPULATE_WRITE after MADV_HUGEPAGE, 2 one write a page without the
# advice, 3 populate without it): issue 27's kinds under mode 0 with detect(), detectInto() and
# device-only results in one round (a second was cut: the device budget left after refused
# starts); then the scenes with
# results over a megabyte under detect() and dropped results, the four modes in two rounds of
# alternating order. Run from the repository root with `.gl` and `build-pack` carried
# (build-pack/bins.tar.xz: build-carry/s85x/vkcollide_bench, Release, stripped;
# build-pack/cgal.tar.xz: data/cgal-run). Analyse from results/h200_2026-12-07 with
# `python3 analyse46.py kinds run51` and `python3 analyse46.py touch run51`.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run51; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run51.tgz run51; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $W/host.txt 2>&1
nproc >> $W/host.txt; grep -m1 "model name" /proc/cpuinfo >> $W/host.txt; uname -r >> $W/host.txt
grep -E "MemTotal|MemFree|AnonHugePages" /proc/meminfo >> $W/host.txt
timeout 60 build-pack/probe 30 16 > $W/probe30.csv 2>&1; log probe30 $?
timeout 60 build-pack/probe 8 16 > $W/probe8.csv 2>&1; log probe8 $?
BIN=build-carry/s85x/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-bar,twisted-ribbon,ball-cloth,drape-flap-b,stack-touching,wall-touching,spheres-60x10K,bunnies-2x75K-twin
for r in a; do
  v=default,into,device-only; [ $r = b ] && v=device-only,into,default
  timeout 120 $BIN $B --frames 8 --warmup-ms 400 --variants $v --scenes $KINDS \
    --csv $W/kinds-$r.csv --profile $W/kinds-$r"_profile.csv" > $W/kinds-$r.txt 2>&1; log kinds-$r $?
done
BIG=stack-mating,stack-touching,wall-touching,pile-deep,spheres-100x10K,cad-mating
touch() {  # $1: round, $2: VKC_EXP_TOUCH mode
  VKC_EXP_TOUCH=$2 timeout 90 $BIN $B --frames 8 --warmup-ms 300 --variants default,dropped --scenes $BIG \
    --csv $W/touch-$1-m$2.csv --profile $W/touch-$1-m$2_profile.csv > $W/touch-$1-m$2.txt 2>&1; log touch-$1-m$2 $?
}
touch a 0; touch a 1; touch a 2; touch a 3; touch b 3; touch b 2; touch b 1; touch b 0
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run51.tgz run51
cat $W/log.txt; cat $W/gpu.txt; cat $W/host.txt; awk -F, '$1>=3' $W/probe30.csv
