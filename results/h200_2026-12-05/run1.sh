#!/usr/bin/env bash
# H200 run 1 of 2026-12-05: the bench set (default, grid-tuned, device-only) and proximity.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $OUT/gpu.txt 2>&1
start=$(date +%s)
for set in ${SETS:-tuning}; do
  timeout ${SET_LIMIT:-400} $B/vkcollide_bench --data data/cgal --cache /tmp/bc --set $set \
      --variants default,grid-tuned,device-only --frames 6 --threads 16 --warmup-ms 1000 \
      --csv $OUT/$set.csv --profile $OUT/${set}_profile.csv > $OUT/$set.txt 2>&1
  echo "$set rc=$? at $(( $(date +%s) - start )) s" >> $OUT/log.txt
done
[ -n "$NO_PROX" ] || timeout 120 $B/vkcollide_bench_proximity --scenes pair,cloth-391k,cloth-524k --factors 0.1,0.5 \
    --frames 10 --warmup-ms 1500 --threads 16 --passes --reference --csv $OUT/proximity.csv > $OUT/proximity.txt 2>&1
echo "proximity rc=$? at $(( $(date +%s) - start )) s" >> $OUT/log.txt
cat $OUT/log.txt
