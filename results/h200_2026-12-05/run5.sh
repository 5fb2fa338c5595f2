#!/usr/bin/env bash
# H200 run 5 of 2026-12-05: the sweep's repeat checks from which cell depth (an experiment's
# environment switch, VKCOLLIDE_SWEEP_DEDUPE), the budget read only where a subgroup checks.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run5; mkdir -p $W
start=$(date +%s)
for d in 64 1024 4294967295; do
  for set in tuning held-out; do
    VKCOLLIDE_SWEEP_DEDUPE=$d timeout 100 $B/vkcollide_bench --data data/cgal --cache /tmp/bc --set $set --variants default \
        --frames 6 --threads 16 --warmup-ms 600 --csv $W/${set}_d$d.csv --profile $W/${set}_d${d}_profile.csv > $W/${set}_d$d.txt 2>&1
    echo "$set d=$d rc=$? at $(( $(date +%s) - start )) s" >> $W/log.txt
    tar czf $OUT/run5.tgz -C $W .
  done
done
cat $W/log.txt
