#!/usr/bin/env bash
# Device run 7 of 2026-12-06 (session 49): where the setup and fill passes spend their time.
#   build-carry/base/  vkcollide_bench at 2e945b3 (the session's start)
#   build-carry/new/   the fit's bounds reduced per workgroup (one atomic per field)
#   build-carry/<exp>/ new with one piece of the setup or fill pass done twice (the second
#                      time adding 0 or into a never-true sink, so results are unchanged):
#     setup-atomics2  the count loop's atomics; setup-covers2 its cover tests;
#     setup-header2   the per-subgroup 64-bit budget atomic; fill-atomics2 the slot atomics
#                     (with their covers tests); fill-compute2 covers, depth and key
# Each pass's time grows by what the doubled piece costs. device-only, one invocation each.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run7; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run7.tgz run7; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
H=deep-blobs,pile-shapes,bunnies-2x75K
n=0
for b in base new setup-atomics2 setup-covers2 setup-header2 fill-atomics2 fill-compute2 new base; do
  n=$((n + 1)); o=$n-$b
  timeout 60 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants device-only --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run7.tgz run7
cat $W/log.txt
