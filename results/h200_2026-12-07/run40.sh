#!/usr/bin/env bash
# Device run 40 (session 59): every bench scene at the session's last code (s69 = f942633, the
# same code as 9a2f96b: the pairs named during the GPU in pieces, from 32,768 pairs), detect()
# and detectInto(); then the scenes with many pairs with each result released. Run from the
# repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s69, vkcollide_bench, Release, stripped
#   build-pack/cgal.tar.xz  data/cgal-run
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run40; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run40.tgz run40; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s69/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
timeout 200 build-carry/s69/vkcollide_bench $B --frames 8 --warmup-ms 600 --variants default,into --csv $W/all.csv \
  --profile $W/all_profile.csv > $W/all.txt 2>&1; log all $?
timeout 100 build-carry/s69/vkcollide_bench $B --frames 8 --warmup-ms 300 --variants dropped \
  --scenes stack-mating,stack-touching,wall-touching,cad-mating,pile-deep,spheres-60x10K-dense --csv $W/dropped.csv \
  --profile $W/dropped_profile.csv > $W/dropped.txt 2>&1; log dropped $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run40.tgz run40
cat $W/log.txt
