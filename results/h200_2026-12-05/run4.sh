#!/usr/bin/env bash
# H200 run 4 of 2026-12-05: the sweep's repeat checks from which cell depth (an experiment's
# environment switch, VKCOLLIDE_SWEEP_DEDUPE), with the budget read once per subgroup;
# Contexts created in a loop; the stability and cell tests one test case per process.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry
start=$(date +%s)
timeout 60 $B/ctxloop 60 0 > $OUT/ctx_novalidation.txt 2>&1; echo "ctx rc=$?" >> $OUT/log.txt
timeout 60 $B/ctxloop 60 1 > $OUT/ctx_validation.txt 2>&1; echo "ctx validation rc=$?" >> $OUT/log.txt
for d in 64 256 1024 4294967295; do
  for set in tuning held-out; do
    VKCOLLIDE_SWEEP_DEDUPE=$d timeout 150 $B/vkcollide_bench --data data/cgal --cache /tmp/bc --set $set --variants default \
        --frames 6 --threads 16 --warmup-ms 600 --csv $OUT/${set}_d$d.csv --profile $OUT/${set}_d${d}_profile.csv > $OUT/${set}_d$d.txt 2>&1
    echo "$set d=$d rc=$? at $(( $(date +%s) - start )) s" >> $OUT/log.txt
  done
done
for t in vkcollide_stability_tests vkcollide_cells_tests; do
  $B/$t --list-test-names-only | grep -v '^$' | grep -v "test cases" | sed 's/\\/\\\\/g; s/,/\\,/g; s/\[/\\[/g' > /tmp/$t.names
  while IFS= read -r name; do
    timeout 60 $B/$t "$name" -d yes > /tmp/one.txt 2>&1; rc=$?
    echo "rc=$rc $(grep -E '^[0-9.]+ s: ' /tmp/one.txt | tail -1)" >> $OUT/$t.txt
    [ $rc -ne 0 ] && cat /tmp/one.txt >> $OUT/${t}_failures.txt
  done < /tmp/$t.names
  echo "$t at $(( $(date +%s) - start )) s" >> $OUT/log.txt
done
cat $OUT/log.txt
