#!/usr/bin/env bash
# Device run 43 (session 60), two experiments against s70 (a8c27fc, the code of 2b3b6e4):
#  1. the sweep pass dispatching its deep cells before the shallow tiles (longest first):
#     every bench scene, s70 and s71x in turns (rounds a: s70 first, b: s71x first);
#  2. where a deforming scene's per-frame vertex update goes (deforming scenes only):
#     A s70; B s71x; C s71x with VKC_EXP_DEFER (updateVertices measures no shape, leaving it
#     to the detection's one loop over every stale mesh); D C with VKC_EXP_INLINE=32768 (the
#     fewest vertices of a copy chunk raised from 16,384). Both knobs are experiment-only
#     (never committed: experiments/session60_update_knobs.diff).
# s71x = 2b3b6e4 + the dispatch order + the knobs; s72 = 2a839ab (pair_naming). Run from the repository root with `.gl`
# and `build-pack` carried (build-carry/s70, s71x: vkcollide_bench, vkcollide_bench_frames,
# Release, stripped; data/cgal-run).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run43; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run43.tgz run43; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s70/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
sweep() {  # $1: round, $2: build
  timeout 150 build-carry/$2/vkcollide_bench $B --frames 6 --warmup-ms 400 --variants default --csv $W/sweep-$1-$2.csv \
    --profile $W/sweep-$1-$2_profile.csv > $W/sweep-$1-$2.txt 2>&1; log sweep-$1-$2 $?
}
sweep a s70; sweep a s71x; sweep b s71x; sweep b s70
SCENES=deform-blobs,deform-armadillo-bunny,deform-tori,deform-pair-100K,deform-pair-1M
one() {  # $1: round, $2: policy name, $3: build, then environment
  local r=$1 name=$2 b=$3; shift 3
  env "$@" timeout 100 build-carry/$b/vkcollide_bench $B --frames 10 --warmup-ms 600 --variants default,into --scenes $SCENES \
    --csv $W/update-$r-$name.csv --profile $W/update-$r-$name"_profile.csv" > $W/update-$r-$name.txt 2>&1; log update-$r-$name $?
}
# SKIP_UPDATE=1: experiments 1 and 3 only (a short device call).
for r in $([ -n "$SKIP_UPDATE" ] || echo a b); do
  if [ $r = b ]; then order="D C B A"; else order="A B C D"; fi
  for p in $order; do
    case $p in
      A) one $r A s70 X=0;;
      B) one $r B s71x X=0;;
      C) one $r C s71x VKC_EXP_DEFER=1;;
      D) one $r D s71x VKC_EXP_DEFER=1 VKC_EXP_INLINE=32768;;
    esac
  done
done
# vkcollide_bench_frames' update rows, s71x's with update-pair-idle (a deforming pair's host
# frame after 0.5 ms idle), under each policy.
timeout 60 build-carry/s70/vkcollide_bench_frames --vertices 25000 --methods none --frames 60 --threads 16 > $W/frames-A.csv 2>&1; log frames-A $?
timeout 60 build-carry/s71x/vkcollide_bench_frames --vertices 25000 --methods none --frames 60 --threads 16 > $W/frames-B.csv 2>&1; log frames-B $?
VKC_EXP_DEFER=1 timeout 60 build-carry/s71x/vkcollide_bench_frames --vertices 25000 --methods none --frames 60 --threads 16 > $W/frames-C.csv 2>&1; log frames-C $?
VKC_EXP_DEFER=1 VKC_EXP_INLINE=32768 timeout 60 build-carry/s71x/vkcollide_bench_frames --vertices 25000 --methods none --frames 60 --threads 16 > $W/frames-D.csv 2>&1; log frames-D $?
# 3. What naming the pairs during the GPU saves: s72 (2a839ab), default against after-fence
#    (ReliableSettings::pair_naming AfterFence), detect() keeping every result.
timeout 100 build-carry/s72/vkcollide_bench $B --frames 8 --warmup-ms 400 --variants default,after-fence \
  --scenes stack-mating,stack-touching,wall-touching,cad-mating --csv $W/naming.csv --profile $W/naming_profile.csv > $W/naming.txt 2>&1; log naming $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run43.tgz run43
cat $W/log.txt
