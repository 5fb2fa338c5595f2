#!/usr/bin/env bash
# Prepared as device run 26 of 2026-12-06 (session 53) and NOT RUN: no GPU was lent (every
# start refused or failed). Most needed first: (a') the result's two arrays made ready side by
# side (637f007) against one after the other; (a) the bracketed grid tuner against the fixed
# grid on both sets, warm (what decides GridTuning::Auto); (b) the tuners on the touching stack
# and the pile, each variant its own invocation, timestamped, beside the GPU's clocks sampled
# every 20 ms by nvidia-smi; (c) where detect()'s result memory goes inside a detection, piece
# by piece (session53_prepare_trace.patch: VKCOLLIDE_TRACE_PREPARE prints allocation, advice,
# parallel touch and resize per array; VKCOLLIDE_PREPARE_MODE=nohuge skips the huge-page
# advice). Run from the repository root with `.gl` and `build-pack` carried:
#   build-carry/trace/  vkcollide_bench at 962764c + session53_prepare_trace.patch (the old tuner)
#   build-carry/new/    vkcollide_bench at 84dd7c3 + the same patch (the bracketed tuner)
#   build-carry/p1/     vkcollide_bench at 637f007 (the two arrays side by side)
#   build-carry/s54/    vkcollide_bench at b06bbed (session 54: the host's sorted pairs cross
#                       the bus at 8 bytes a pair; compare pairs-to-host with p1's, (a''))
#   (stripped, `tar -cJf build-pack/bins.tar.xz build-carry`)
#   build-pack/cgal.tar.xz  data/cgal less ChineseDragon, mushroom and the spheres, as
#                       cgal-run/ (`tar -C data -cJf build-pack/cgal.tar.xz cgal-run`): the
#                       checkout with data/cgal itself is over the device tool's 64 MiB
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run26; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run26.tgz run26; }
stamp() { echo "$1 $(date +%s.%N)" >> $W/stamps.txt; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag >> $W/gpu.txt 2>&1
grep -E "MemFree|AnonHugePages|HugePages_Free" /proc/meminfo >> $W/gpu.txt
O=build-carry/trace/vkcollide_bench; X=build-carry/new/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
timeout 60 $X $B --frames 6 --warmup-ms 1000 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
# (a') the result's two arrays side by side (p1) against one after the other (new), alternated;
# (a'') with s54 (8-byte host pairs: pairs-to-host, detect(), detectInto()) in the same loop
for r in 1; do for b in new p1 s54; do
  timeout 60 build-carry/$b/vkcollide_bench $B --frames 6 --warmup-ms 1000 --variants default,dropped,into \
    --scenes stack-mating,stack-touching,wall-touching --csv $W/$r-$b.csv --profile $W/$r-$b\_profile.csv > $W/$r-$b.txt 2>&1; log $r-$b $?
done; done
# (a)
timeout 170 $X $B --frames 6 --warmup-ms 1000 --variants default,grid-tuned --csv $W/tuner.csv --profile $W/tuner_profile.csv > $W/tuner.txt 2>&1; log tuner $?
# (b)
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,pstate,utilization.gpu,clocks_throttle_reasons.active --format=csv,noheader -lms 20 > $W/clocks.csv 2>&1 &
SMI=$!
grid() {
  k=0
  for v in new:default old:grid-tuned new:grid-tuned new:cells-x0.7 new:default; do
    k=$((k+1)); b=${v%%:*}; v=${v#*:}; n=grid-$1-$k-$b-$v; bin=$X; [ $b = old ] && bin=$O
    stamp "$n begin"
    timeout 60 $bin $B --frames 30 --warmup-ms 300 --variants $v --scenes $1 --csv $W/$n.csv --profile $W/$n\_profile.csv > $W/$n.txt 2>&1; rc=$?
    stamp "$n end"; log $n $rc
  done
}
# (c)
prep() {
  VKCOLLIDE_TRACE_PREPARE=1 VKCOLLIDE_PREPARE_MODE=$1 timeout 100 $X $B --frames 6 --warmup-ms 1000 --variants default,dropped \
    --scenes stack-mating,stack-touching --csv $W/prep-$1.csv --profile $W/prep-$1\_profile.csv > $W/prep-$1.txt 2> $W/prep-$1.trace; log prep-$1 $?
}
grid stack-touching; prep huge; grid pile-shapes; kill $SMI; prep nohuge
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run26.tgz run26
cat $W/log.txt; head -c 1500 $W/prep-huge.trace; grep -hE "stack|pile" $W/prep-*.txt $W/grid-*.txt; tail -40 $W/tuner.txt
