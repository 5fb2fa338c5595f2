#!/usr/bin/env bash
# The engine loop on the GPU machine, in one go (about a minute): updateVertices per
# million vertices and its parts, and detect() against submit()/collect() against the pipelined loop, for
# a deforming 100K and 1M pair, both methods. One CSV; the columns are explained at the top
# of tools/bench/bench_frames.cpp.
#
#   tools/bench/run_frames_h200.sh [OUT]     (default: $OUT if set, else bench-out)
#   Environment: BENCH (default build/tools/vkcollide_bench_frames), THREADS (16), FRAMES (60)
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:-${OUT:-bench-out}}"
bench="${BENCH:-build/tools/vkcollide_bench_frames}"
threads="${THREADS:-16}"; frames="${FRAMES:-60}"
mkdir -p "$out"
{
  "$bench" --vertices 1000000 --triangles 100000 --frames "$frames" --threads "$threads"
  "$bench" --vertices 1000000 --triangles 1000000 --frames "$frames" --threads "$threads" | grep -E '^(detect|submit|pipelined),'
} | tee "$out/frames.csv"
