#!/usr/bin/env bash
# Device run 30 (session 56): every bench scene, detect() (default) and detectInto() (into), at
# main's build. Run from the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s58/vkcollide_bench at main's HEAD (Release, stripped;
#                           `tar -cJf build-pack/bins.tar.xz build-carry`)
#   build-pack/cgal.tar.xz  data/cgal-run
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run30; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run30.tgz run30; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
N=build-carry/s58/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $N $B --frames 6 --warmup-ms 1000 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
timeout 200 $N $B --frames 8 --warmup-ms 600 --variants default,into --csv $W/all.csv --profile $W/all_profile.csv > $W/all.txt 2>&1
log all $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run30.tgz run30
cat $W/log.txt
