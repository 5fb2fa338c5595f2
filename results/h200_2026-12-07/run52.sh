#!/usr/bin/env bash
# Device run 52 (session 64), on run 51's machine while it was still held: run 51's second
# kinds round (the variants in the opposite order), pipelined frames for the deforming scenes,
# and a third round of the touch modes 0 and 1 on the scenes where they differed most. Same
# binary and carry as run51.sh. Analyse with `python3 analyse46.py kinds run52` and
# `python3 analyse46.py touch run52`.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run52; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run52.tgz run52; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
BIN=build-carry/s85x/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-bar,twisted-ribbon,ball-cloth,drape-flap-b,stack-touching,wall-touching,spheres-60x10K,bunnies-2x75K-twin
timeout 120 $BIN $B --frames 8 --warmup-ms 400 --variants device-only,into,default --scenes $KINDS \
  --csv $W/kinds-b.csv --profile $W/kinds-b_profile.csv > $W/kinds-b.txt 2>&1; log kinds-b $?
timeout 60 $BIN $B --frames 8 --warmup-ms 400 --variants pipelined --scenes deform-armadillo-bunny,deform-pair-100K,cloth-fold-720K \
  --csv $W/kinds-p.csv --profile $W/kinds-p_profile.csv > $W/kinds-p.txt 2>&1; log kinds-p $?
for m in 1 0 0 1; do
  r=c; [ -f $W/touch-c-m$m.csv ] && r=d
  VKC_EXP_TOUCH=$m timeout 60 $BIN $B --frames 8 --warmup-ms 300 --variants default --scenes stack-mating,wall-touching,cad-mating \
    --csv $W/touch-$r-m$m.csv --profile $W/touch-$r-m$m"_profile.csv" > $W/touch-$r-m$m.txt 2>&1; log touch-$r-m$m $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run52.tgz run52
cat $W/log.txt; cat $W/gpu.txt
