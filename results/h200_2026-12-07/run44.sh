#!/usr/bin/env bash
# Device run 44 (session 61): the sweep's walks read shared memory where a cell is large.
#   s71x: 7b2ac5c's sweep (the deep cells dispatched first; the run-43 build of the branch)
#   s73:  + the deep sweep keeps each entry's box with its sorted index and loads an entry
#         from global memory only for a pair it may keep (cells_deep.glsl.inc)
#   s74:  + the shallow tiles load the vertex indices of cells of 64 entries or more into
#         shared memory (cells_sweep_shallow.glsl.inc, kIndexedCell)
# Every bench scene in rounds a (s71x s73 s74) and b (s74 s73 s71x); `sort-gpu` against
# `default` on the scenes with few pairs; then every scene at s74,
# detect() and detectInto(), for docs/results.md. Run from the repository root with `.gl` and
# `build-pack` carried (build-pack/bins.tar.xz: build-carry/s71x, s73, s74, vkcollide_bench,
# Release, stripped; build-pack/cgal.tar.xz: data/cgal-run). Analyse with
# `python3 analyse43.py sweep run44` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run44; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run44.tgz run44; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s74/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
sweep() {  # $1: round, $2: build
  timeout 150 build-carry/$2/vkcollide_bench $B --frames 6 --warmup-ms 400 --variants default --csv $W/sweep-$1-$2.csv \
    --profile $W/sweep-$1-$2_profile.csv > $W/sweep-$1-$2.txt 2>&1; log sweep-$1-$2 $?
}
sweep a s71x; sweep a s73; sweep a s74; sweep b s74; sweep b s73; sweep b s71x
# Below kGpuPairSortFrom (4,096 pairs) the host sorts and computes the responses on one thread
# (0.06-0.17 ms for 600-1,700 pairs): the GPU's sort and responses (`sort-gpu`) on the scenes
# with few pairs, in two rounds.
FEW=deform-blobs,deform-armadillo-bunny,deform-tori,deform-pair-100K,bunnies-2x75K,bunnies-2x75K-twin,mixed-gpu,twisted-ribbon,drape-flap-b
for r in a b; do
  v=default,sort-gpu; [ $r = b ] && v=sort-gpu,default
  timeout 100 build-carry/s74/vkcollide_bench $B --frames 10 --warmup-ms 400 --variants $v --scenes $FEW --csv $W/few-$r.csv \
    --profile $W/few-$r"_profile.csv" > $W/few-$r.txt 2>&1; log few-$r $?
done
timeout 200 build-carry/s74/vkcollide_bench $B --frames 8 --warmup-ms 600 --variants default,into --csv $W/all.csv \
  --profile $W/all_profile.csv > $W/all.txt 2>&1; log all $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run44.tgz run44
cat $W/log.txt
