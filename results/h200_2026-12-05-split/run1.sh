#!/usr/bin/env bash
# Device run 1 of 2026-12-05 (session 44): the pair pass split in two (exp-split, 182bf1c:
# the pair pass queues what the filter leaves, the exact pass decides the queue) against
# main. Three builds, in build-pack/bins.tar.xz:
#   build-carry/base/      6dd498a (main's detection code: one pair pass with the exact test inside)
#   build-carry/split/     182bf1c: the pair pass and the exact pass
#   build-carry/split-o2/  182bf1c + 487620e: and orient2d's exact fallback in registers
# Both bench sets, default settings, each build; the split's pair pass with the exact
# decision off (exact-cpu: the first kernel alone); the exact tests on NVIDIA.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run1; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run1.tgz run1; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
bench() {  # build, set, variants, output name
  timeout 100 $B/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set $2 --variants $3 --frames 6 --threads 16 \
      --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
bench split tuning default split_tuning
bench base tuning default base_tuning
bench split-o2 tuning default split-o2_tuning
bench split held-out default split_held-out
bench base held-out default base_held-out
bench split-o2 held-out default split-o2_held-out
timeout 60 $B/split-o2/vkcollide_exact_gpu_tests -s "exact GPU triangle pairs decide as the CPU on random and adversarial pairs" > $W/exact_gpu_pairs_o2.txt 2>&1; log exact_gpu_pairs_o2 $?
timeout 60 $B/split/vkcollide_exact_decision_tests "exact decision: GPU and CPU give the same pairs and responses on resting\, coplanar and folded contacts" > $W/exact_decision.txt 2>&1; log exact_decision $?
for b in split base; do
  timeout 80 $B/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all \
      --scenes stack-mating,stack-touching,cad-mating,spheres-60x10K-dense,pile-shapes --variants exact-cpu --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/${b}_exact-cpu.csv --profile $W/${b}_exact-cpu_profile.csv > $W/${b}_exact-cpu.txt 2>&1; log ${b}_exact-cpu $?
done
bench split tuning default split_tuning2
bench base tuning default base_tuning2
cat $W/log.txt
