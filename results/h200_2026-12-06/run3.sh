#!/usr/bin/env bash
# Device run 3 of 2026-12-06 (session 48).
#   build-carry/base/  vkcollide_bench at 65d6404 (the session's start)
#   build-carry/new/   the result's fresh arrays in transparent huge pages (resizeFresh:
#                      madvise before the parallel touch); the exact GPU tests with the
#                      rounding's steps compared one by one on full doubles
#   build-carry/thp    36 MB of fresh pairs touched by 16 threads, with and without the advice
# First the host's huge-page settings and the page-touch figures, then the exact tests on
# NVIDIA (which step of the rounding differs there), then both benches, two rounds in
# opposite orders.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run3; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run3.tgz run3; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
{ uname -r; nproc; for f in enabled defrag; do echo "$f: $(cat /sys/kernel/mm/transparent_hugepage/$f)"; done; } > $W/host.txt 2>&1
build-carry/thp 16 > $W/thp16.txt 2>&1; log thp $?
timeout 90 build-carry/new/vkcollide_exact_gpu_tests > $W/exact_gpu.txt 2>&1; log exact_gpu $?
bench() {  # build, variants, output name
  timeout 80 build-carry/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants $2 --scenes $H --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$3.csv --profile $W/$3_profile.csv > $W/$3.txt 2>&1; log $3 $?
}
H=stack-mating,stack-touching,pile-shapes,bunnies-2x75K
bench base default base_a
bench new default new_a
bench new default new_b
bench base default base_b
gzip $W/*_profile.csv; tar -C /tmp -czf $OUT/run3.tgz run3
cat $W/log.txt $W/host.txt $W/thp16.txt; grep -E "rounding|differ|FAILED|passed|failed" $W/exact_gpu.txt | head -30
