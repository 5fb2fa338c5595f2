#!/usr/bin/env bash
# Device run 2 of 2026-12-05 (session 46): responses computed on the GPU, after run 1: the
# exact sign tests in a five-term expansion in registers (run 1's accumulator array sat in
# local memory, and its corrections from 5 ulps off missed by one ulp on NVIDIA), the
# arithmetic in a program of its own dispatched over the triangles in a pair only.
#   build-carry/new/  main with the device responses (ResponseSource::Auto: the GPU computes
#                     the host result's responses wherever it sorts its pairs), its bench and
#                     the test executables that compare the GPU's responses with the CPU's
# First the tests on NVIDIA (bit-for-bit responses, rounding, engine reader, 5,000 partners),
# then the bench, same binary: default (GPU responses) against responses-cpu (the narrow
# phase's, the path before), and the device-only frames with and without device responses,
# two rounds in opposite orders.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry/new; W=/tmp/run2; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run2.tgz run2; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
t() {  # executable, output name, test spec (none: every test)
  timeout 120 $B/$1 ${3:+"$3"} > $W/$2.txt 2>&1; log $2 $?
}
t vkcollide_exact_gpu_tests rounding "rounded GPU division\, square root and float rounding equal the CPU's"
t vkcollide_device_pairs_tests device_pairs ""
t vkcollide_exact_decision_tests pair_sort "pair sort*"
t vkcollide_engine_loop_tests engine_loop ""
t vkcollide_stability_tests partners "reliable: a triangle with 5\,000 partners*"
bench() {  # variants, output name, scenes
  timeout 110 $B/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants $1 --scenes $3 --frames 8 \
      --threads 16 --warmup-ms 1000 --csv $W/$2.csv --profile $W/$2_profile.csv > $W/$2.txt 2>&1; log $2 $?
}
H=stack-mating,stack-touching,wall-touching,cad-mating,pile-deep,spheres-60x10K-dense,spheres-100x10K,pile-shapes,deform-pair-100K,bunnies-2x75K
bench default,responses-cpu,device-only,device-responses a $H
bench device-responses,device-only,responses-cpu,default b $H
cat $W/log.txt
