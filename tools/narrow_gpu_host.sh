#!/usr/bin/env bash
# Narrow-phase benchmark for the 16-core GPU host (docs/narrow_phase.md).
# Runs every workload of tools/bench/bench_narrow.cpp that the issue names, on the three
# entries (80-byte records, 32-byte records with a TriangleSource, candidate pairs), with
# self-collision off (vkcollide's default) and on (the peers' benchmarks), on 1, 4, 8 and
# 16 threads; prints the tables and writes one CSV per workload.
#
#   bash tools/narrow_gpu_host.sh [path/to/vkcollide_bench_narrow] [output folder]
#
# The gpu-* rows need the Vulkan device (on the H200 host set VK_DRIVER_FILES as
# results/h200_2026-11-29/README.md says); pass SKIP_GPU=1 to leave them out. About 5 minutes on 16 cores.
set -euo pipefail
bench=${1:-build/tools/vkcollide_bench_narrow}
out=${2:-narrow_gpu_host}
mkdir -p "$out"
echo "host: $(nproc) threads, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
all="--paths records,lean,pairs --self off,on --repeat 9"

echo "== 1M candidates: the deep overlap (two spheres of 600K triangles, 85 % overlap) =="
"$bench" --scenes deep --sizes 1200000 --modes near,all --threads 1,4,8,16 $all --csv "$out/deep.csv"
echo "== the 60-mesh pile (596K triangles) =="
"$bench" --scenes pile --modes near,all --threads 1,4,8,16 $all --csv "$out/pile.csv"
echo "== surfaces crossing all over (a sphere and a copy turned by 3 degrees, 300K triangles) =="
"$bench" --scenes twin --sizes 300000 --modes all --threads 1,4,8,16 $all --csv "$out/twin.csv"
echo "== the demo scene =="
"$bench" --scenes demo --modes near,contact --threads 1,4,8,16 $all --csv "$out/demo.csv"
echo "== without a workspace (every call allocates, as CollisionWorld calls it today), 16 threads =="
"$bench" --scenes deep --sizes 1200000 --modes near --threads 16 --paths records,lean,pairs --self off,on --repeat 9 \
    --fresh --csv "$out/deep_fresh.csv"

if [ "${SKIP_GPU:-0}" != 1 ]; then
    echo "== the GPU broad phase's own records: demo, pile, deep overlap of two 1.28M-triangle spheres =="
    "$bench" --scenes gpu-demo,gpu-pile --resolution 1024 --threads 1,16 $all --csv "$out/gpu.csv"
    "$bench" --scenes gpu-deep --sizes 2560000 --resolution 1024 --threads 1,16 $all --csv "$out/gpu_deep.csv"
fi
echo "CSV files in $out/"
