#!/usr/bin/env bash
# Quick start 2: install what is missing, build warning-free (-Werror) and run the whole
# suite. Each check runs once, in the one build that can make it:
#   1. Release: the library, the command-line tool, the samples and the benchmarks (built,
#      not run) at -O3, then the tests labelled `release`: the samples' smoke tests
#      (validation layer on), vkcollide_bench on a user's meshes and frontier.sh's input
#      checks (tests/bench), and the installed package (an engine-like consumer against the
#      static install and against a shared libvkcollide built from scratch). The package's
#      consumer cannot link a sanitized library, and the samples are what a user runs, so
#      they are tested as shipped.
#   2. Everything else under AddressSanitizer + UndefinedBehaviorSanitizer (Debug, -O1, so
#      that assertions are on and the host's share of the GPU tests stays fast; -g1: the
#      line tables the sanitizers' stack traces need, without -g's variables, which cost a
#      third of the compiling): the library, the command-line tool, every test, host and
#      GPU, on the Vulkan device found (lavapipe in CI) with the Khronos validation layer and
#      synchronization validation on (any message fails a test), and the fuzz targets' seeds
#      replayed. The Vulkan driver and the layer are not instrumented; tools/sanitize/ says
#      how their leaks are told apart from ours.
#   3. VKCOLLIDE_HOST_ONLY configured (not built): the host-only build, which needs no shader
#      tools, stays configurable; its code and tests are the host part of build 2.
# 48 minutes from a fresh clone on an idle two-core machine (docs/stability.md, "CI coverage").
#
#   tools/test.sh [BUILD_ROOT]   the folder the build folders go in (or VKCOLLIDE_BUILD_ROOT;
#                                default: the checkout), so that a read-only checkout is testable
set -euo pipefail
cd "$(dirname "$0")/.."
src="$PWD"
build_root="${1:-${VKCOLLIDE_BUILD_ROOT:-$src}}"
mkdir -p "$build_root" && cd "$build_root"
bash "$src/tools/deps.sh"
jobs=$(nproc)
start=$(date +%s)
elapsed() { echo "($(( $(date +%s) - start )) s so far)"; }

echo "== Release: library, CLI, samples, benchmarks; samples' smoke tests and the installed package =="
cmake -S "$src" -B build-ci -G Ninja -DCMAKE_BUILD_TYPE=Release -DVKCOLLIDE_WERROR=ON >/dev/null
cmake --build build-ci -j "$jobs" --target vkcollide vkcollide_cli vkcollide_samples vkcollide_sample_tests vkcollide_benchmarks
ctest --test-dir build-ci -j "$jobs" -L release --output-on-failure --no-tests=error
elapsed

# cmake/Sanitizers.cmake compiles the sanitizers' options into every executable. No
# samples, no benchmarks (never run, so nothing for the sanitizers to see) and no install
# (the package test's consumer is not sanitized): build 1 has them.
echo "== everything else under AddressSanitizer + UndefinedBehaviorSanitizer (validation layer on) =="
cmake -S "$src" -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" -DVKCOLLIDE_WERROR=ON \
  -DVKCOLLIDE_SANITIZE=address,undefined -DVKCOLLIDE_BUILD_SAMPLES=OFF -DVKCOLLIDE_BUILD_BENCHMARKS=OFF -DVKCOLLIDE_INSTALL=OFF >/dev/null
cmake -S "$src" -B build-host-only -G Ninja -DVKCOLLIDE_HOST_ONLY=ON -DVKCOLLIDE_WERROR=ON >/dev/null
cmake --build build-asan -j "$jobs"
ctest --test-dir build-asan -j "$jobs" --output-on-failure --no-tests=error
elapsed
