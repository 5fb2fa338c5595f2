#!/usr/bin/env bash
# Device run 29 (session 56). Run from the repository root with `.gl` and `build-pack` carried:
#   build-pack/bins.tar.xz  build-carry/s58/vkcollide_bench (Release, stripped): c776800 + 177c9a8 (headers), the responses'
#                           counts zeroed by a compute step instead of a fill, and experiment switches
#                           (environment variables, read once):
#                           VKCOLLIDE_EXP_COPY_AT=late|bucket|sort  where the pairs' copy to the
#                             host is recorded: after the responses (c776800's order), after
#                             responses-bucket, or right after the sort (unset: sort)
#                           VKCOLLIDE_EXP_SPAN_ONLY=1  every pass's end stamp at TOP_OF_PIPE
#                             but the last (no per-pass BOTTOM stamps: pass times meaningless)
#                           VKCOLLIDE_EXP_VALIDATE_TWICE=1  the host's naming loop of the GPU's
#                             sorted pairs run three times, each timed to stderr
#                           VKCOLLIDE_EXP_STREAM=1  its stores of the pairs non-temporal
#   build-pack/cgal.tar.xz  data/cgal-run
# PART=A: four combinations (copy late or after the sort, every stamp or span only) on seven scenes, rounds a (base first) and b (base last).
# PART=AB runs both, A first.
# PART=B: every bench scene, default and into, the copy where COPY_AT says (default late: c776800's order).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run29$PART; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run29$PART.tgz run29$PART; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
N=build-carry/s58/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $N $B --frames 6 --warmup-ms 1000 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
if [[ "$PART" == *A* ]]; then
  S=stack-mating,stack-touching,wall-touching,pile-shapes,deep-blobs,deform-pair-100K,bunnies-2x75K
  run() {  # name copy_at span_only
    env VKCOLLIDE_EXP_COPY_AT=$2 ${3:+VKCOLLIDE_EXP_SPAN_ONLY=1} timeout 120 $N $B --frames 8 --warmup-ms 400 \
      --variants default,into --scenes $S --csv $W/$1.csv --profile $W/$1_profile.csv > $W/$1.txt 2>&1; log $1 $?
  }
  run a1-late late ""; run a2-sort sort ""; run a3-sort-span sort 1; run a4-late-span late 1
  # The host's naming of the sorted pairs run three times a detection (VKCOLLIDE_EXP_VALIDATE_TWICE:
  # stderr's "EXP validate rep"): the first against the later ones (workers awake, memory warm).
  # With VKCOLLIDE_EXP_STREAM=1 its stores are non-temporal (no read for ownership).
  for st in "" 1; do
    env VKCOLLIDE_EXP_VALIDATE_TWICE=1 ${st:+VKCOLLIDE_EXP_STREAM=1} timeout 60 $N $B --frames 4 --warmup-ms 200 \
      --variants into,default --scenes stack-mating,stack-touching --csv $W/exp-validate$st.csv > $W/exp-validate$st.txt 2>&1
    log exp-validate$st $?
  done
  run b4-late-span late 1; run b3-sort-span sort 1; run b2-sort sort ""; run b1-late late ""
fi
if [[ "$PART" == *B* ]]; then
  timeout 300 env VKCOLLIDE_EXP_COPY_AT=${COPY_AT:-late} $N $B --frames 8 --warmup-ms 600 --variants default,into \
    --csv $W/all.csv --profile $W/all_profile.csv > $W/all.txt 2>&1; log all $?
fi
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run29$PART.tgz run29$PART
cat $W/log.txt
