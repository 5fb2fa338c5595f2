#!/usr/bin/env bash
# Device run 12 of 2026-12-06 (session 49): where the sweep spends its time.
#   build-carry/new/   vkcollide_bench at 420c82f (entries' cells found by the sweep)
#   build-carry/<exp>/ new with one piece of the sweep done twice, into a never-true sink:
#     sweep-loop2   the first scan over the cell (the entry's depth end moved up by 1, so
#                   that the compiler keeps both); sweep-counts2 four more same-address
#                   atomics per subgroup (adding 0); sweep-head2 the entry's cell search,
#                   its offsets and its record read again for entry e ^ 1
# device-only, one invocation each.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run12; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run12.tgz run12; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
H=deep-blobs,pile-shapes,spheres-60x10K-dense,stack-mating,bunnies-2x75K
n=0
for b in new sweep-loop2 sweep-counts2 sweep-head2 new; do
  n=$((n + 1)); o=$n-$b
  timeout 60 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants device-only --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run12.tgz run12
cat $W/log.txt
