#!/usr/bin/env bash
# Device run 3 of 2026-12-05 (session 44): what the pair pass's filter costs now that the
# exact pass decides what it leaves. build-carry/expf/vkcollide_bench is main (3094658,
# ExactPass::Auto) + an experiment, not committed (exp_filter.patch in this folder): VKC_EXP_FILTER=1 the
# whole filter (main's), 2 only the plane sides (each triangle's vertices against the
# other's plane), 3 the plane sides and, where a sign is uncertain, the projections (no
# Guigue-Devillers interval step), 0 no filter (every canonical candidate to the exact pass).
# Each mode twice, interleaved, on contact scenes and piles.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run3; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run3.tgz run3; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
S=stack-mating,stack-touching,cad-mating,wall-touching,spheres-60x10K-dense,spheres-60x10K,pile-shapes,pile-deep
for round in a b; do
  for m in 1 2 3 0; do
    VKC_EXP_FILTER=$m timeout 60 $B/expf/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --scenes $S --variants default \
        --frames 6 --threads 16 --warmup-ms 1000 --csv $W/mode${m}_$round.csv --profile $W/mode${m}_${round}_profile.csv \
        > $W/mode${m}_$round.txt 2>&1; log mode${m}_$round $?
  done
done
cat $W/log.txt
