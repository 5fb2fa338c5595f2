#!/usr/bin/env bash
# Device run 46 (session 62): detect()'s result memory made ready during the GPU's wait for
# results of every size from 16 KB (it was 1 MB, and only for GPU-sorted pairs): a kept
# result's successor gets new pages from the kernel, which faulted on one thread after the
# wait (spheres-60x10K, 32K pairs: narrow phase 0.60 ms for detect(), 0.10 for detectInto()).
#   s76: 02a0868 (main before the change)
#   s77: the change (prepareResultMemory from 16 KB, both pair paths)
# Every bench scene under `default` in rounds a (s76 s77) and b (s77 s76); then issue 27's
# scene kinds at s77 under detectInto(), device-only results, pipelined frames and dropped
# results, for docs/results.md. Run from the repository root with `.gl` and `build-pack`
# carried (build-pack/bins.tar.xz: build-carry/s76, s77, vkcollide_bench, Release, stripped;
# build-pack/cgal.tar.xz: data/cgal-run). Analyse with `python3 analyse43.py sweep run46`
# and `python3 analyse46.py run46` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run46; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run46.tgz run46; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag > $W/host.txt 2>&1
nproc >> $W/host.txt; grep -m1 "model name" /proc/cpuinfo >> $W/host.txt
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s77/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
sweep() {  # $1: round, $2: build
  timeout 150 build-carry/$2/vkcollide_bench $B --frames 6 --warmup-ms 400 --variants default --csv $W/sweep-$1-$2.csv \
    --profile $W/sweep-$1-$2_profile.csv > $W/sweep-$1-$2.txt 2>&1; log sweep-$1-$2 $?
}
sweep a s76; sweep a s77; sweep b s77; sweep b s76
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-bar,twisted-ribbon,ball-cloth,drape-flap-b,stack-touching,wall-touching,spheres-60x10K,bunnies-2x75K-twin
timeout 200 build-carry/s77/vkcollide_bench $B --frames 8 --warmup-ms 400 --variants default,into,device-only,pipelined,dropped \
  --scenes $KINDS --csv $W/kinds.csv --profile $W/kinds_profile.csv > $W/kinds.txt 2>&1; log kinds $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run46.tgz run46
cat $W/log.txt
