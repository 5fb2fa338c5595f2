#!/usr/bin/env bash
# Device run 8 of 2026-12-06 (session 49): where the setup and fill passes spend their time.
#   build-carry/new/   the fit's bounds reduced per workgroup (run 7's "new")
#   build-carry/<exp>/ new with one more piece of the setup or fill pass done twice (into a
#                      never-true sink, so results are unchanged):
#     setup-fetch2   a neighbour triangle's indices and positions; setup-fp64-2 the
#                    double-precision world transform; setup-sample2 the sampling
#                    coordinates and their error bounds; fill-tri2 a neighbour's triangle
#                    record; fill-offsets2 each covered cell's offsets (the next row's)
# Each pass's time grows by what the doubled piece costs. device-only, one invocation each.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run8; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run8.tgz run8; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
H=deep-blobs,pile-shapes,bunnies-2x75K
n=0
for b in new setup-fetch2 setup-fp64-2 setup-sample2 fill-tri2 fill-offsets2 new; do
  n=$((n + 1)); o=$n-$b
  timeout 60 build-carry/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants device-only --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run8.tgz run8
cat $W/log.txt
