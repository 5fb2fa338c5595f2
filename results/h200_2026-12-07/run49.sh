#!/usr/bin/env bash
# Device run 49 (session 62): issue 27's scene kinds whose pairs the host sorts, at s80
# (= 4694f71, the committed result memory policy: made ready for GPU-sorted results from 16 KB,
# none on the host's pair path; run 47's s78 made it ready there too) under detect() and
# pipelined frames, in two rounds (the variants in opposite orders), for docs/results.md. Run from the repository root with
# `.gl` and `build-pack` carried (build-pack/bins.tar.xz: build-carry/s80/vkcollide_bench;
# data/cgal-run). Analyse with `python3 analyse46.py kinds run49` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run49; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run49.tgz run49; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s80/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
KINDS=deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-ribbon,ball-cloth
for r in a b; do
  v=default,pipelined; [ $r = b ] && v=pipelined,default
  timeout 100 build-carry/s80/vkcollide_bench $B --frames 8 --warmup-ms 400 --variants $v --scenes $KINDS \
    --csv $W/kinds-$r.csv --profile $W/kinds-$r"_profile.csv" > $W/kinds-$r.txt 2>&1; log kinds-$r $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run49.tgz run49
cat $W/log.txt
