#!/usr/bin/env bash
# Device run 4 of 2026-12-05 (session 45): detect()'s result memory made ready during the
# GPU's work (build-carry/new/: prepareResultMemory) against main without it (1cc4a19) and
# the session's start (f3916a9), interleaved, default settings and detectInto().
#   build-carry/base/  f3916a9   build-carry/main/  1cc4a19   build-carry/new/  1cc4a19 + the ready memory
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run4; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run4.tgz run4; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
bench() {  # build, variants, output name, scenes
  timeout 100 $B/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants $2 --scenes $4 --frames 8 \
      --threads 16 --warmup-ms 1000 --csv $W/$3.csv --profile $W/$3_profile.csv > $W/$3.txt 2>&1; log $3 $?
}
H=stack-mating,stack-touching,wall-touching,cad-mating,pile-deep,spheres-60x10K-dense,spheres-100x10K,pile-shapes,deform-pair-100K,bunnies-2x75K
bench new default,into new_a $H; bench main default,into main_a $H; bench base default base_a $H
bench base default base_b $H; bench main default,into main_b $H; bench new default,into new_b $H
cat $W/log.txt
