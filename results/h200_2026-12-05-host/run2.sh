#!/usr/bin/env bash
# Device run 2 of 2026-12-05 (session 45): run 1 again in the other order (base first),
# default and detectInto(); 2 MB pages for the fresh result memory (an experiment); the
# grid tuner on main.
#   build-carry/base/  f3916a9      build-carry/main/  1cc4a19
#   build-carry/exp/   1cc4a19 + VKC_EXP_THP=1: resizeFresh asks madvise(MADV_HUGEPAGE) for
#                      the new memory before touching it (not committed)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
B=build-carry; W=/tmp/run2; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run2.tgz run2; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
for f in enabled defrag; do echo "$f: $(cat /sys/kernel/mm/transparent_hugepage/$f)" >> $W/gpu.txt; done
bench() {  # build, set, variants, output name, [scenes]
  timeout 110 $B/$1/vkcollide_bench --data data/cgal --cache /tmp/bc --set $2 --variants $3 ${5:+--scenes $5} --frames 6 \
      --threads 16 --warmup-ms 1000 --csv $W/$4.csv --profile $W/$4_profile.csv > $W/$4.txt 2>&1; log $4 $?
}
bench base tuning default,into base_tuning
bench main tuning default,into main_tuning
bench base held-out default,into base_held-out
bench main held-out default,into main_held-out
C=stack-mating,stack-touching,cad-mating,wall-touching,pile-deep,spheres-60x10K-dense
for round in a b; do
  bench main all default main_contacts_$round $C
  VKC_EXP_THP=1 bench exp all default thp_contacts_$round $C
done
bench main tuning grid-tuned main_tuning_grid
bench main held-out grid-tuned main_held-out_grid
cat $W/log.txt
