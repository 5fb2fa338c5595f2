#!/usr/bin/env bash
# Device run 2 of 2026-12-06: the statistics capture after its two-call queries were folded
# into one helper (queryAll, src/vk/pipeline.cpp): the statistics test and the bench's CSV.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run2; mkdir -p $W
timeout 60 build-carry/new/vkcollide_engine_gpu_tests "pipeline statistics*" > $W/statistics.txt 2>&1; echo "statistics rc=$?" >> $W/log.txt
timeout 60 build-carry/new/vkcollide_bench --data data/cgal --cache /tmp/bc --set all --variants default --scenes bunnies-2x75K \
  --frames 2 --pipeline-stats $W/pipeline_stats.csv > $W/bench.txt 2>&1; echo "bench rc=$?" >> $W/log.txt
tar -C /tmp -czf $OUT/run2.tgz run2; cat $W/log.txt; tail -2 $W/statistics.txt; wc -l $W/pipeline_stats.csv
