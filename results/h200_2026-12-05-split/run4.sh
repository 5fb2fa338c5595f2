#!/usr/bin/env bash
# Device run 4 of 2026-12-05 (session 44): the plane-sides filter as landed (main,
# build-carry/main/) against the whole filter (build-carry/expf/ with VKC_EXP_FILTER=1, the
# behaviour of 3094658), interleaved twice, on contact scenes, piles and small scenes.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run4; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run4.tgz run4; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
S=stack-mating,stack-touching,cad-mating,wall-touching,spheres-60x10K-dense,pile-shapes,pile-deep,deform-pair-100K,bunnies-2x75K
for round in a b; do
  for b in main whole; do
    bin=$B/main/vkcollide_bench; [ $b = whole ] && bin=$B/expf/vkcollide_bench
    VKC_EXP_FILTER=1 timeout 60 $bin --data data/cgal --cache /tmp/bc --set all --scenes $S --variants default \
        --frames 6 --threads 16 --warmup-ms 1000 --csv $W/${b}_$round.csv --profile $W/${b}_${round}_profile.csv \
        > $W/${b}_$round.txt 2>&1; log ${b}_$round $?
  done
done
cat $W/log.txt
