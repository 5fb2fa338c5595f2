#!/usr/bin/env bash
# Device run 45 (session 61): where the GPU's pair sort and responses start to pay
# (kGpuPairSortFrom, 4,096 pairs in the last detection). `sort-gpu` (PairSort::Gpu) against
# `default` (Auto: below 4,096 the host sorts and computes the responses) on every bench
# scene of 900-4,500 pairs, two rounds in both orders, at s73 (= 5f8d709's library: the deep
# sweep's boxes in shared memory). Tuning scenes decide, held-out ones (mixed-gpu-b,
# twisted-ribbon, drape-flap-b) check. Run from the repository root with `.gl` and
# `build-pack` carried (build-carry/s73 in build-pack/bins.tar.xz; data/cgal-run).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run45; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run45.tgz run45; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s73/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
MID=bunnies-2x75K,spheres-2x640K,bunnies-2x75K-deep,deform-pair-1M,mixed-gpu,spheres-8x10K,cloth-fold,mixed-gpu-b,twisted-ribbon,drape-flap-b
for r in a b; do
  v=default,sort-gpu; [ $r = b ] && v=sort-gpu,default
  timeout 150 build-carry/s73/vkcollide_bench $B --frames 10 --warmup-ms 400 --variants $v --scenes $MID --csv $W/mid-$r.csv \
    --profile $W/mid-$r"_profile.csv" > $W/mid-$r.txt 2>&1; log mid-$r $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run45.tgz run45
cat $W/log.txt
