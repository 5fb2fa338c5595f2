#!/usr/bin/env bash
# Device run 22 of 2026-12-06 (session 51): the fill's table where a workgroup's footprints crowd.
#   build-carry/base/   vkcollide_bench at 658be6c (session 50's end)
#   build-carry/gateN/  run 21's table (1,024 places), its places' atomics issued together, used
#                       by a workgroup whose footprint boxes add up to N times the cells of the box
#                       around them all or more (gate0: every workgroup); each footprint alone elsewhere
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run22; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run22.tgz run22; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --frames 6 --threads 16 --warmup-ms 1000"
# A fresh machine runs its first work cold (run 19): a throwaway invocation first.
timeout 60 build-carry/base/vkcollide_bench $B --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
H=deep-blobs,deep-bunny-elephant,pile-shapes,pile-deep,spheres-60x10K-dense,bunnies-2x75K,stack-mating,stack-touching,wall-touching,deform-pair-1M,spheres-2x640K,bunnies-14x75K,pile-small
n=0
for b in base gate0 gate1 gate2 base gate2 gate1 gate0; do
  n=$((n + 1)); o=$n-$b
  timeout 90 build-carry/$b/vkcollide_bench $B --variants device-only --scenes $H --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
rm -f $W/case.txt; gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run22.tgz run22
cat $W/log.txt
