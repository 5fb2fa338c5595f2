#!/usr/bin/env bash
# Device run 24 of 2026-12-06 (session 52): where detect()'s host result spends its time on the
# scenes of many pairs, and fresh result memory mapped by the kernel in one call per task.
#   build-carry/stat/   vkcollide_bench at b6f2bf1 (DetectStats::host.prepare_ms: the "prepare" row) + the
#                       folded-cloth scenes (cloth-fold, cloth-fold-720K)
#   build-carry/over/   stat + resizeFresh's tasks on huge-page boundaries, resize()'s one-thread pass as
#                       the first task while the others map the pages from the back with
#                       MADV_POPULATE_WRITE (where the kernel does; otherwise written first, as before)
#   build-carry/probe/  memprobe: fresh memory's costs on this host (experiments/session52_memprobe.cpp, g++ -O2 -std=c++20 -pthread)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run24; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run24.tgz run24; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
(uname -r; nproc; lscpu | grep -E "Model name|Socket|NUMA node\(s\)|L3") > $W/host.txt 2>&1
timeout 60 build-carry/probe/memprobe 16 > $W/memprobe16.txt 2>&1; log memprobe16 $?

B="--data data/cgal-run --cache /tmp/bc --set all --frames 6 --threads 16 --warmup-ms 1000"
# A fresh machine runs its first work cold (run 19): a throwaway invocation first.
timeout 60 build-carry/stat/vkcollide_bench $B --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
H=stack-mating,stack-touching,wall-touching,cad-mating,spheres-60x10K-dense
n=0
for b in stat over over stat; do
  n=$((n + 1)); o=$n-$b
  timeout 100 build-carry/$b/vkcollide_bench $B --variants default,into --scenes $H --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
# The folded cloths (the folded-cloth kind: a 720K cloth through itself).
for b in stat over; do
  timeout 100 build-carry/$b/vkcollide_bench $B --variants device-only,default --scenes cloth-fold,cloth-fold-720K --csv $W/fold-$b.csv --profile $W/fold-${b}_profile.csv > $W/fold-$b.txt 2>&1; log fold-$b $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run24.tgz run24
cat $W/log.txt; cat $W/host.txt; cat $W/memprobe16.txt
