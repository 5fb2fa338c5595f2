#!/usr/bin/env bash
# Device run 3 of 2026-12-05 (session 45): new memory for detect()'s result touched a byte
# per page, then one pass (build-carry/new/), against touching it in full, zeroing and copying
# (run 1-2's main, 1cc4a19) and the session's start (f3916a9), interleaved; the grid tuner on
# cold clocks (no warm-up, 40 frames) and again on the scenes it did not speed up in run 2.
#   build-carry/base/  f3916a9   build-carry/main/  1cc4a19   build-carry/new/  the working tree
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run3; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run3.tgz run3; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
bench() {  # build, variants, output name, scenes, [frames warm-up]
  timeout 100 $B/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants $2 --scenes $4 --frames ${5:-6} \
      --threads 16 --warmup-ms ${6:-1000} --csv $W/$3.csv --profile $W/$3_profile.csv > $W/$3.txt 2>&1; log $3 $?
}
H=stack-mating,stack-touching,wall-touching,cad-mating,pile-deep,pile-shapes,spheres-60x10K-dense,spheres-100x10K,spheres-60x10K,deep-blobs
bench base default base_a $H; bench main default main_a $H; bench new default new_a $H
bench new default new_b $H; bench main default main_b $H; bench base default base_b $H
G=stack-mating,stack-touching,deep-blobs,spheres-60x10K-dense
bench new default,grid-tuned cold $G 40 0
T=stack-touching,pile-shapes,deform-tori,mixed-gpu,spheres-60x10K-dense,spheres-8x10K,mixed-gpu-b,deform-pair-100K
bench new default,grid-tuned tuner_a $T; bench new grid-tuned,default tuner_b $T
cat $W/log.txt
