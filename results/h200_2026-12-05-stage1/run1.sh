#!/usr/bin/env bash
# H200 run 1 of 2026-12-05 (session 43): the exact path's stage 1 in registers.
#   build-carry/base/  6dd498a (the code of main before this session: exact fallbacks all in
#                      the scratch-memory expansion)
#   build-carry/       the exact path in two stages (stage 1 in registers), its CLI and the
#                      exact test executables
# Both sets once per build, the exact tests on NVIDIA (one case per process), the
# contact scenes without the exact decision, proximity, then the tuning set again per
# build if time is left.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz  # build-carry/, packed (the carried files are limited to 64 MiB)
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run1; mkdir -p $W
start=$(date +%s)
# After every step the folder is packed into $OUT again (one file: at most 8 come back), so
# a timeout still returns what ran.
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run1.tgz run1; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
prox() {  # build folder, output name
  timeout 100 $1/vkcollide_bench_proximity --scenes pair,cloth-391k,cloth-524k --factors 0.1,0.5 \
      --frames 10 --warmup-ms 1500 --threads 16 --passes --reference --csv $W/$2.csv > $W/$2.txt 2>&1; log $2 $?
}
bench() {  # build folder, set, variants, output name
  timeout 200 $1/vkcollide_bench --data data/cgal --cache /tmp/bc --set $2 --variants $3 --frames 6 --threads 16 \
      --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
bench $B tuning default,device-only new_tuning
bench $B/base tuning default,device-only base_tuning
bench $B held-out default,device-only new_held-out
bench $B/base held-out default,device-only base_held-out
timeout 120 $B/vkcollide_exact_gpu_tests -s "exact GPU triangle pairs decide as the CPU on random and adversarial pairs" > $W/exact_gpu_pairs.txt 2>&1; log exact_gpu_pairs $?
timeout 120 $B/vkcollide_exact_gpu_tests -s "exact GPU predicates return the CPU's signs" > $W/exact_gpu_points.txt 2>&1; log exact_gpu_points $?
# The pair pass without the exact decision (filter only; the CPU decides), for what the
# exact tests still cost; proximity (the pair pass is shared).
timeout 100 $B/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --scenes stack-mating,stack-touching,cad-mating,wall-touching \
    --variants exact-cpu --frames 6 --threads 16 --warmup-ms 1000 --csv $W/new_exact-cpu.csv --profile $W/new_exact-cpu_profile.csv \
    > $W/new_exact-cpu.txt 2>&1; log new_exact-cpu $?
prox $B new_proximity
timeout 150 $B/vkcollide_exact_decision_tests --list-test-names-only 2>/dev/null | grep -v '^$' | head -40 > $W/decision_cases.txt
while IFS= read -r c; do
  timeout 60 $B/vkcollide_exact_decision_tests "$(printf "%s" "$c" | sed "s/,/\\\\,/g")" >> $W/exact_decision.txt 2>&1; log "decision ${c:0:40}" $?
done < $W/decision_cases.txt
# Second rounds where time is left (clocks).
if [ $(( $(date +%s) - start )) -lt 380 ]; then bench $B tuning default new_tuning2; bench $B/base tuning default base_tuning2; fi
cat $W/log.txt
