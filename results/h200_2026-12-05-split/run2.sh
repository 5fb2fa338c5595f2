#!/usr/bin/env bash
# Device run 2 of 2026-12-05 (session 44): main with the exact pass (3094658, ExactPass::Auto)
# against the one-kernel base, and where the stack's first kernel spends its time.
#   build-carry/base/  6dd498a: one pair pass, the exact decision inside
#   build-carry/main/  3094658: the exact pass (Auto), orient2d's fallback in registers
#   build-carry/exp/   3094658 + experiments, not committed: VKC_EXP_NOFILTER=1 turns the
#                      filter off (every canonical candidate to the exact pass);
#                      vkcollide_bench_noscan has kCellsDedupeBudget 0 (the canonical
#                      check's backward scan off: duplicates it would drop reach the exact
#                      pass and the sort, which drops them; same pairs)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run2; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run2.tgz run2; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
bench() {  # binary, set, variants, output name, [scenes]
  timeout 100 $1 --data data/cgal --cache /tmp/bc --set $2 --variants $3 ${5:+--scenes $5} --frames 6 --threads 16 \
      --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
bench $B/main/vkcollide_bench tuning default,device-only main_tuning
bench $B/base/vkcollide_bench tuning default,device-only base_tuning
bench $B/main/vkcollide_bench held-out default,device-only main_held-out
bench $B/base/vkcollide_bench held-out default,device-only base_held-out
C=stack-mating,stack-touching,cad-mating,wall-touching,spheres-60x10K-dense
bench $B/main/vkcollide_bench all exact-inline,exact-queued main_passes $C,deform-pair-100K,bunnies-2x75K,pile-shapes
bench $B/exp/vkcollide_bench_noscan all default exp_noscan $C
VKC_EXP_NOFILTER=1 bench $B/exp/vkcollide_bench all default exp_nofilter $C
for b in main base; do
  timeout 80 $B/$b/vkcollide_bench_proximity --scenes pair,cloth-391k --factors 0.1,0.5 --frames 10 --warmup-ms 1500 --threads 16 \
      --passes --reference --csv $W/${b}_proximity.csv > $W/${b}_proximity.txt 2>&1; log ${b}_proximity $?
done
cat $W/log.txt
