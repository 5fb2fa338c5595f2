#!/usr/bin/env bash
# Device run 56 (session 66): the one pass of few pairs (PairSort::Auto below
# kGpuPairSortFrom: spirv/cells/small_sort.comp.glsl) on the kind the targets name
# (asked as nvidia-h200; gpu.txt says which card came). One build, s90 = 298ed90 (the
# pass and its follow-ups, its tests at the limit), Release, stripped: the bench and two test executables.
#   tests-*.txt: the pass against the device-pairs passes and the CPU's sort, to the bit, on
#     this driver (the same test cases CI runs on lavapipe).
#   small-<round>: every bench scene with fewer than 4,096 pairs, `default` (the one pass)
#     against `sort-cpu` (PairSort::Cpu: the host's sort and responses, which Auto ran below
#     4,096 pairs before), three rounds, the variants' order reversed in b.
#   kinds-a, kinds-b: issue 27's kinds, `default`, `into`, `device-only` (b reversed);
#     kinds-p: pipelined frames of the deforming scenes.
# Run from the repository root with `.gl` and `build-pack` carried (build-pack/bins.tar.xz:
# build-carry/s90/; build-pack/cgal.tar.xz: data/cgal-run). Analyse with
# `python3 analyse46.py modes run56 ...` and `python3 analyse46.py kinds run56` from
# results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run56; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run56.tgz run56; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
nproc > $W/host.txt; grep -m1 "model name" /proc/cpuinfo >> $W/host.txt; uname -r >> $W/host.txt
S=build-carry/s90
timeout 100 $S/vkcollide_exact_decision_tests "pair sort*" > $W/tests-pair-sort.txt 2>&1; log tests-pair-sort $?
timeout 60 $S/vkcollide_broadphase_tests "reliable: few pairs sorted in one pass*" > $W/tests-one-pass.txt 2>&1; log tests-one-pass $?
BIN=$S/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
SMALL=bunnies-2x75K,twisted-ribbon,deform-armadillo-bunny,deform-pair-100K,drape-flap-b,ball-cloth,twisted-bar,deform-tori,deform-blobs,spheres-8x10K,bunnies-2x75K-deep,deform-pair-1M,spheres-2x640K,mixed-gpu
small() {  # $1: round, $2: variants
  timeout 150 $BIN $B --frames 10 --warmup-ms 300 --variants $2 --scenes $SMALL \
    --csv $W/small-$1.csv --profile $W/small-$1_profile.csv > $W/small-$1.txt 2>&1; log small-$1 $?
}
small a default,sort-cpu; small b sort-cpu,default; small c default,sort-cpu
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-ribbon,stack-touching,wall-touching
for r in a b; do
  v=default,into,device-only; [ $r = b ] && v=device-only,into,default
  timeout 120 $BIN $B --frames 8 --warmup-ms 400 --variants $v --scenes $KINDS \
    --csv $W/kinds-$r.csv --profile $W/kinds-$r"_profile.csv" > $W/kinds-$r.txt 2>&1; log kinds-$r $?
done
timeout 60 $BIN $B --frames 8 --warmup-ms 400 --variants pipelined --scenes deform-armadillo-bunny,deform-pair-100K,cloth-fold-720K \
  --csv $W/kinds-p.csv --profile $W/kinds-p_profile.csv > $W/kinds-p.txt 2>&1; log kinds-p $?
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run56.tgz run56
cat $W/log.txt; cat $W/gpu.txt $W/host.txt; tail -4 $W/tests-*.txt
