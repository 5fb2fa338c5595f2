#!/usr/bin/env bash
# Device run 48 (session 62): runs 46-47 moved host times of scenes whose code path the
# change leaves as it was (deform-armadillo-bunny: nothing made ready, yet its vertex update
# slower too), so two binaries differ by more than the change. Here one binary, s79 (s78 with
# experiments/session62_old_prepare.diff), runs both policies: `old` with
# VKC_EXP_OLD_PREPARE=1 (02a0868's: made ready from 1 MB, GPU-sorted pairs only, on the
# executor) and `new` without (s78's). Every bench scene under `default`, four rounds in the
# orders old new / new old / old new / new old. Run from the repository root with `.gl` and
# `build-pack` carried (build-pack/bins.tar.xz: build-carry/s79; data/cgal-run). Analyse with
# `python3 analyse46.py sweep run48` from results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run48; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run48.tgz run48; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 build-carry/s79/vkcollide_bench $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
sweep() {  # $1: round, $2: policy (old, new)
  ( [ $2 = old ] && export VKC_EXP_OLD_PREPARE=1
    timeout 150 build-carry/s79/vkcollide_bench $B --frames 6 --warmup-ms 400 --variants default --csv $W/sweep-$1-$2.csv \
      --profile $W/sweep-$1-$2_profile.csv > $W/sweep-$1-$2.txt 2>&1 ); log sweep-$1-$2 $?
}
sweep a old; sweep a new; sweep b new; sweep b old; sweep c old; sweep c new; sweep d new; sweep d old
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run48.tgz run48
cat $W/log.txt
