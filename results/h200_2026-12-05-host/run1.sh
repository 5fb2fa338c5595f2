#!/usr/bin/env bash
# Device run 1 of 2026-12-05 (session 45): main (432bf68..1cc4a19: detect()'s fresh result
# memory touched in parallel, the filter skipped before the exact pass where it rejects
# little, the cell stage's programs made when first recorded) against f3916a9, both sets,
# then the contact scenes again in the other order.
#   build-carry/base/  f3916a9      build-carry/main/  1cc4a19
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run1; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run1.tgz run1; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
bench() {  # build, set, variants, output name, [scenes]
  timeout 110 $B/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set $2 --variants $3 ${5:+--scenes $5} --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
bench main tuning default,device-only,into main_tuning
bench base tuning default,device-only,into base_tuning
bench main held-out default,device-only,into main_held-out
bench base held-out default,device-only,into base_held-out
C=stack-mating,stack-touching,cad-mating,wall-touching,pile-deep,spheres-60x10K-dense,pile-shapes
bench base all default base_contacts_b $C
bench main all default main_contacts_b $C
cat $W/log.txt
