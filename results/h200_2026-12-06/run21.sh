#!/usr/bin/env bash
# Device run 21 of 2026-12-06 (session 51): the fill's slots taken per cell of a workgroup.
#   build-carry/base/      vkcollide_bench at 658be6c (session 50's end)
#   build-carry/new/       the fill counts its workgroup's footprints per cell in a table in
#                          shared memory (1,024 places), takes each cell's slots with one
#                          atomic and places the footprints from there; bench and tests
#   build-carry/fill2048/  new with a table of 2,048 places
#   build-carry/both/      new, and the setup counting its footprints through the same table;
#                          bench and cell tests
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run21; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run21.tgz run21; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --frames 6 --threads 16 --warmup-ms 1000"
# A fresh machine runs its first work cold (run 19): a throwaway invocation first.
timeout 60 build-carry/base/vkcollide_bench $B --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
timeout 90 build-carry/new/vkcollide_device_pairs_tests > $W/device_pairs.txt 2>&1; log device_pairs $?
timeout 90 build-carry/new/vkcollide_engine_loop_tests > $W/engine_loop.txt 2>&1; log engine_loop $?
H=deep-blobs,deep-bunny-elephant,pile-shapes,pile-deep,spheres-60x10K-dense,bunnies-2x75K,stack-mating,stack-touching,wall-touching,deform-pair-1M
n=0
for b in base new both fill2048 base both new fill2048; do
  n=$((n + 1)); o=$n-$b
  timeout 90 build-carry/$b/vkcollide_bench $B --variants device-only --scenes $H --csv $W/$o.csv --profile $W/${o}_profile.csv > $W/$o.txt 2>&1; log $o $?
done
# Every cell test case in a process of its own (run 18: one process cannot create more than ~23 validated contexts there).
for T in new both; do
  build-carry/$T/vkcollide_cells_tests --list-test-names-only | grep -v '^$' | sed 's/,/\\,/g; s/\[/\\[/g; s/\]/\\]/g' > $W/names.txt
  while IFS= read -r c; do
    timeout 60 build-carry/$T/vkcollide_cells_tests "$c" > $W/case.txt 2>&1; rc=$?
    echo "rc=$rc $(grep -E 'All tests passed|test cases' $W/case.txt | head -1) :: $c" >> $W/cells-$T.txt
    [ $rc -ne 0 ] && cat $W/case.txt >> $W/failures-$T.txt
  done < $W/names.txt
  log cells-$T 0
done
rm -f $W/case.txt; gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run21.tgz run21
cat $W/log.txt; grep -E "passed|failed" $W/device_pairs.txt $W/engine_loop.txt; grep -c "^rc=0" $W/cells-*.txt; grep -v "^rc=0" $W/cells-*.txt | cut -c1-200
