#!/usr/bin/env bash
# H200 run 2 of 2026-12-05: the held-out set, the pathological piles through the CLI, GPU tests.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; S=results/h200_2026-12-05/scenes
start=$(date +%s)
timeout 200 $B/vkcollide_bench --data data/cgal --cache /tmp/bc --set held-out \
    --variants default,grid-tuned,device-only --frames 6 --threads 16 --warmup-ms 1000 \
    --csv $OUT/held-out.csv --profile $OUT/held-out_profile.csv > $OUT/held-out.txt 2>&1
echo "held-out rc=$? at $(( $(date +%s) - start )) s" >> $OUT/log.txt
{
for args in "$S/pile-2200.obj $S/cross.obj --self 1" "$S/pile-3000.obj $S/cross.obj --self 1" \
            "$S/pile-3000.obj $S/cross.obj --self 1 --max-candidate-pairs 268435456" \
            "$S/fan-300.obj --self 1" "$S/fan-300.obj --self 1 --resolution 250" \
            "$S/fan-300.obj --self 1 --resolution 500" "$S/fan-300.obj --self 1 --resolution 1000"; do
  echo "== vkcollide detect $args --frames 3"
  timeout 60 $B/vkcollide detect $args --frames 3 2>&1 | tail -4
done
} > $OUT/piles.txt 2>&1
echo "piles at $(( $(date +%s) - start )) s" >> $OUT/log.txt
for t in vkcollide_stability_tests vkcollide_cells_tests vkcollide_exact_decision_tests; do
  timeout 150 $B/$t -d yes > $OUT/$t.txt 2>&1; echo "$t rc=$? at $(( $(date +%s) - start )) s" >> $OUT/log.txt
done
cat $OUT/log.txt
