#!/usr/bin/env bash
# Device run 27 (session 55): session 53's run 26, not run then for want of a GPU (every
# start refused or failed), with a newer build and the direction variants added to (a); two
# calls, each under the device tool's 600 s: PART=1 runs the warm-up, (a) and (a'), PART=2 (b)
# and (c). Most needed first: (a') the result's two arrays made ready side by
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
#   build-carry/s55/    vkcollide_bench at 3c7c236 (preparePipelines, the dir-* variants)
#   build-carry/s56/    s55 with the reliable method's axis tilted 20 degrees where a quarter of the
#                       area would be seen edge-on (02528c8)
#   build-carry/s54/    vkcollide_bench at b06bbed (session 54: the host's sorted pairs cross
#                       the bus at 8 bytes a pair; compare pairs-to-host with p1's, (a''))
#   (stripped, `tar -cJf build-pack/bins.tar.xz build-carry`)
#   build-pack/cgal.tar.xz  data/cgal less ChineseDragon, mushroom and the spheres, as
#                       cgal-run/ (`tar -C data -cJf build-pack/cgal.tar.xz cgal-run`): the
#                       checkout with data/cgal itself is over the device tool's 64 MiB
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz; mkdir -p data; tar -C data -xJf build-pack/cgal.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run27-${PART:-1}; mkdir -p $W
start=$(date +%s)
log() { echo "$1 rc=$2 at $(( $(date +%s) - start )) s" >> $W/log.txt; tar -C /tmp -czf $OUT/run27-${PART:-1}.tgz run27-${PART:-1}; }
stamp() { echo "$1 $(date +%s.%N)" >> $W/stamps.txt; }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
cat /sys/kernel/mm/transparent_hugepage/enabled /sys/kernel/mm/transparent_hugepage/defrag >> $W/gpu.txt 2>&1
grep -E "MemFree|AnonHugePages|HugePages_Free" /proc/meminfo >> $W/gpu.txt
O=build-carry/trace/vkcollide_bench; X=build-carry/new/vkcollide_bench
B="--data data/cgal-run --cache /tmp/bc --set all --threads 16"
if [ "${PART:-1}" = 1 ]; then
N=build-carry/s55/vkcollide_bench
timeout 60 $N $B --frames 6 --warmup-ms 1000 --variants device-only --scenes spheres-60x10K-dense > $W/0-warm.txt 2>&1; log warm $?
# (a) the figures for docs/results.md: s55 (the automatic axis, as before); s56 (the reliable
# method's axis tilted 20 degrees) with the bracketed grid tuner against its fixed grid (what
# decides GridTuning::Auto) and a direction oblique to every axis
timeout 200 $N $B --frames 6 --warmup-ms 600 --variants default --csv $W/s55.csv --profile $W/s55_profile.csv > $W/s55.txt 2>&1; log s55 $?
timeout 300 build-carry/s56/vkcollide_bench $B --frames 6 --warmup-ms 600 --variants default,grid-tuned,dir-oblique --csv $W/s56.csv --profile $W/s56_profile.csv > $W/s56.txt 2>&1; log s56 $?
# (a') the result's two arrays side by side (p1) against one after the other (new); (a'') the
# 8-byte host pairs (s54: pairs-to-host, detect(), detectInto())
for b in new p1 s54; do [ $(( $(date +%s) - start )) -gt 500 ] && break
  timeout 60 build-carry/$b/vkcollide_bench $B --frames 6 --warmup-ms 1000 --variants default,dropped,into \
    --scenes stack-mating,stack-touching,wall-touching --csv $W/1-$b.csv --profile $W/1-$b\_profile.csv > $W/1-$b.txt 2>&1; log 1-$b $?
done
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run27-1.tgz run27-1
cat $W/log.txt; grep -hE "^(tuning|held)" $W/s55.txt $W/s56.txt | sort -k2,2 -s | head -140
fi
if [ "${PART:-1}" = 2 ]; then
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
fi
gzip -f $W/*_profile.csv; tar -C /tmp -czf $OUT/run27-${PART:-1}.tgz run27-${PART:-1}
cat $W/log.txt; head -c 1500 $W/prep-huge.trace; grep -hE "stack|pile" $W/prep-*.txt $W/grid-*.txt; tail -40 $W/tuner.txt
