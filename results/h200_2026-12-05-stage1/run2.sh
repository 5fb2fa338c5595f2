#!/usr/bin/env bash
# Device run 2 of 2026-12-05 (session 43), after run 1 showed stage 1 (8d27b33) slower on
# every scene and 74 pairs short on cad-mating (H100). Three builds:
#   build-carry/base/  6dd498a (main's code; 8d27b33 is reverted)
#   build-carry/s1/    8d27b33: orient2d and orient3d's exact fallbacks in registers (stage 1)
#   build-carry/o2/    exp-o2: orient2d's exact fallback alone in registers (no slot arrays)
# (the exact test executables of s1 and o2 with b28c94a's mating-plates family added)
# cad-mating as an OBJ of its world vertices (build-carry/scenes/cad.obj, 192,169 pairs):
# each build's pairs, to find stage 1's missing ones; the exact tests; both bench sets for
# base and o2 (default settings; cut to what device time was left), the pair pass without
# the exact decision, o2's other exact tests.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run2; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run2.tgz run2; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
for b in base s1 o2; do
  timeout 60 $B/$b/vkcollide detect $B/scenes/cad.obj --frames 3 --pairs $W/cad_$b.csv > $W/cad_$b.txt 2>&1; log cad_$b $?
done
timeout 60 $B/base/vkcollide detect $B/scenes/cad.obj --frames 3 --exact cpu --pairs $W/cad_cpu.csv > $W/cad_cpu.txt 2>&1; log cad_cpu $?
# Both builds' exact tests with the mating-plates family (b28c94a), on NVIDIA.
for b in s1 o2; do
  timeout 120 $B/$b/vkcollide_exact_gpu_tests -s "exact GPU triangle pairs decide as the CPU on random and adversarial pairs" > $W/exact_gpu_pairs_$b.txt 2>&1; log exact_gpu_pairs_$b $?
done
bench() {  # build folder, set, variants, output name
  timeout 200 $1/vkcollide_bench --data data/cgal --cache /tmp/bc --set $2 --variants $3 --frames 6 --threads 16 \
      --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
bench $B/o2 tuning default o2_tuning
bench $B/base tuning default base_tuning
bench $B/o2 held-out default o2_held-out
bench $B/base held-out default base_held-out
# The pair pass without the exact decision (filter only, the CPU decides): what the exact
# path's presence in the kernel costs the candidates that never reach it.
for b in base o2; do
  timeout 100 $B/$b/vkcollide_bench --data data/cgal --cache /tmp/bc --set all \
      --scenes stack-mating,stack-touching,cad-mating,spheres-60x10K-dense,pile-shapes --variants default,exact-cpu --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/${b}_exact-cpu.csv --profile $W/${b}_exact-cpu_profile.csv > $W/${b}_exact-cpu.txt 2>&1; log ${b}_exact-cpu $?
done
timeout 120 $B/o2/vkcollide_exact_gpu_tests -s "exact GPU predicates return the CPU's signs" > $W/exact_gpu_points.txt 2>&1; log exact_gpu_points $?
timeout 60 $B/o2/vkcollide_exact_decision_tests "exact decision: GPU and CPU give the same pairs and responses on resting\, coplanar and folded contacts" > $W/exact_decision.txt 2>&1; log exact_decision $?
cat $W/log.txt
