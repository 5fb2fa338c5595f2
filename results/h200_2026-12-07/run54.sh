#!/usr/bin/env bash
# Device run 54 (session 65): issue 27's kinds at eca493d (the library of dc4d6ac) on the kind
# the targets name (asked as nvidia-h200; gpu.txt says which card came), and the
# quiet-lease A/B run 53 could not give. One binary, s88x = eca493d plus
# experiments/session65_switches.diff, Release, stripped. Its switches (unset: main's code):
#   VKC_EXP_OLD_PREPARE=1  the responses' resize() after the pairs' touch, as before dc4d6ac
#     (experiments/session64_old_prepare.diff);
#   VKC_EXP_PIECES=N       the pairs' early copy to the host in at most N pieces (main: 4), each
#     followed by its event and a barrier to the host;
#   VKC_EXP_COPY_STAGE=1   that barrier and event over the transfer stage, not every command.
#   kinds-a, kinds-b: the kinds, `default`, `into` and `device-only`, the variants' order
#     reversed in b; kinds-p: pipelined frames of the deforming scenes; kinds-d: `dropped`
#     (each result released before the next detection, as an engine's loop does) on the
#     scenes whose results pass a megabyte.
#   order-<round>-<new|old>: run 53's A/B, four rounds alternating.
#   pieces-<round>-<mode>: the early copy's pieces and its barrier's stage (p4 = main, p2, p1,
#     cs = p4 with VKC_EXP_COPY_STAGE), `default`, the scenes with early copies.
#   tq-*.csv: the transfer-queue probe (experiments/session65_transfer_queue_probe.cpp, built
#     here as build-pack/tq_probe): a 17 MB copy to host memory beside a compute load, on the
#     main queue and on a transfer-only family's queue.
# Run from the repository root with `.gl` and `build-pack` carried (build-pack/bins.tar.xz:
# build-carry/s88x/vkcollide_bench; build-pack/cgal.tar.xz: data/cgal-run). Analyse with
# `python3 analyse46.py kinds run54` and `python3 analyse46.py order run54` from
# results/h200_2026-12-07.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run54; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run54.tgz run54; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
nproc > $W/host.txt; grep -m1 "model name" /proc/cpuinfo >> $W/host.txt; uname -r >> $W/host.txt
BIN=build-carry/s88x/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
for it in 4000 8000; do timeout 60 build-pack/tq_probe 17 $it 25 > $W/tq-$it.csv 2>&1; log tq-$it $?; done
timeout 60 $BIN $B --frames 4 --warmup-ms 800 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
KINDS=stack-mating,pile-shapes,deep-bunny-elephant,cloth-fold-720K,deform-armadillo-bunny,deform-pair-100K,bunnies-2x75K,twisted-bar,twisted-ribbon,ball-cloth,drape-flap-b,stack-touching,wall-touching,spheres-60x10K,bunnies-2x75K-twin
BIG=stack-mating,stack-touching,wall-touching,pile-deep,spheres-100x10K,cad-mating
for r in a b; do
  v=default,into,device-only; [ $r = b ] && v=device-only,into,default
  timeout 120 $BIN $B --frames 8 --warmup-ms 400 --variants $v --scenes $KINDS \
    --csv $W/kinds-$r.csv --profile $W/kinds-$r"_profile.csv" > $W/kinds-$r.txt 2>&1; log kinds-$r $?
done
timeout 60 $BIN $B --frames 8 --warmup-ms 400 --variants pipelined --scenes deform-armadillo-bunny,deform-pair-100K,cloth-fold-720K \
  --csv $W/kinds-p.csv --profile $W/kinds-p_profile.csv > $W/kinds-p.txt 2>&1; log kinds-p $?
timeout 60 $BIN $B --frames 8 --warmup-ms 400 --variants dropped --scenes $BIG,pile-shapes \
  --csv $W/kinds-d.csv --profile $W/kinds-d_profile.csv > $W/kinds-d.txt 2>&1; log kinds-d $?
order() {  # $1: round, $2: new or old
  local e=""; [ $2 = old ] && e="VKC_EXP_OLD_PREPARE=1"
  env $e timeout 60 $BIN $B --frames 10 --warmup-ms 300 --variants default --scenes $BIG \
    --csv $W/order-$1-$2.csv --profile $W/order-$1-$2_profile.csv > $W/order-$1-$2.txt 2>&1; log order-$1-$2 $?
}
order a new; order a old; order b old; order b new; order c new; order c old; order d old; order d new
pieces() {  # $1: round, $2: mode
  local e=""; case $2 in p2) e="VKC_EXP_PIECES=2";; p1) e="VKC_EXP_PIECES=1";; cs) e="VKC_EXP_COPY_STAGE=1";; esac
  env $e timeout 60 $BIN $B --frames 10 --warmup-ms 300 --variants default --scenes stack-mating,stack-touching,wall-touching,cad-mating \
    --csv $W/pieces-$1-$2.csv --profile $W/pieces-$1-$2_profile.csv > $W/pieces-$1-$2.txt 2>&1; log pieces-$1-$2 $?
}
pieces a p4; pieces a p1; pieces a p2; pieces a cs; pieces b cs; pieces b p2; pieces b p1; pieces b p4
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run54.tgz run54
cat $W/log.txt; cat $W/gpu.txt $W/host.txt
