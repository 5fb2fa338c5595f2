#!/usr/bin/env bash
# Quick start 2: install what is missing, build warning-free (-Werror) and run the whole
# suite. Each test runs once, in the one build that can make its check (its label says
# which: tests/CMakeLists.txt):
#   1. Release: the library, the command-line tool, the samples and the benchmarks (built,
#      not run) at -O3, then the tests labelled `release`: every GPU test but the sanitized
#      build's (lavapipe, Khronos validation layer and synchronization validation on: any
#      message fails a test), the samples' smoke tests, vkcollide_bench on a user's meshes
#      and frontier.sh's input checks, and the installed package (an engine-like consumer
#      against the static install and against a shared libvkcollide configured and built
#      from scratch; the consumer cannot link a sanitized library).
#   2. Under AddressSanitizer + UndefinedBehaviorSanitizer (Debug, -O1, so that assertions
#      are on and the host's share of the GPU tests stays fast; -g1: the line tables the
#      sanitizers' stack traces need, without -g's variables, which cost a third of the
#      compiling), the tests labelled `sanitized`: every host test, the fuzz targets' seeds
#      replayed (the world's on lavapipe with validation), and the GPU executables that reach
#      each room's host code (vkcollide_add_test SANITIZED: the context and device layer on
#      lavapipe and on a fake driver, the engine's synchronisation and lifetimes, peeling's
#      passes, both sampling backends, contacts, proximity, device pairs, an engine's loop).
#      The Vulkan driver and the layer are not instrumented; tools/sanitize/ says how their
#      leaks are told apart from ours.
#   3. VKCOLLIDE_HOST_ONLY configured (not built): the host-only build, which needs no shader
#      tools, stays configurable; its code and tests are the host part of build 2.
# Everything compiles in batches (CMake unity builds: about a third of the compiling), the
# tests' own sources at -O1 (Release) and -O0 (sanitized; the library and the tests'
# references keep their optimisation), the tools' and samples' own sources at -O1 in
# Release (compiled and smoke-tested here, measured in builds of their own), Catch2's
# runner as Catch2 ships it compiled, and in the sanitized build without UBSan's checks:
# they doubled those sources' compiling (the narrow tests' batch 24 s -> 12 s) and would check
# the tests' code, not the library's, which keeps them, as the test support does (ASan stays
# on everywhere). A compiler cache for this run (ccache, in BUILD_ROOT/build-ccache) builds
# the shared package from build 1's objects, and the shader cache beside it
# (build-ccache/shaders, cmake/CompileShader.cmake) compiles each GLSL program once for all
# three builds.
# Minutes from a fresh clone on an idle two-core machine: docs/stability.md, "CI coverage".
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

# The cache's paths are kept relative to the folder holding the sources and the builds,
# so the package test's shared build (beside build-ci) finds build-ci's objects.
CCACHE_BASEDIR="$src"
while [[ "$PWD/" != "$CCACHE_BASEDIR/"* && "$CCACHE_BASEDIR" != / ]]; do CCACHE_BASEDIR="$(dirname "$CCACHE_BASEDIR")"; done
export CCACHE_BASEDIR CCACHE_DIR="$PWD/build-ccache" CCACHE_NOHASHDIR=1
export VKCOLLIDE_SHADER_CACHE_DIR="$PWD/build-ccache/shaders"
export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
unity=(-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 -DVKCOLLIDE_UNITY_LIBRARY=ON)

echo "== Release: library, CLI, samples, benchmarks; the GPU tests, samples' smoke tests and the installed package =="
cmake -S "$src" -B build-ci -G Ninja -DCMAKE_BUILD_TYPE=Release -DVKCOLLIDE_WERROR=ON "${unity[@]}" \
  -DVKCOLLIDE_TEST_COMPILE_OPTIONS=-O1 -DVKCOLLIDE_TOOL_COMPILE_OPTIONS=-O1 >/dev/null
cmake --build build-ci -j "$jobs" --target vkcollide vkcollide_cli vkcollide_samples vkcollide_benchmarks vkcollide_release_suite
# glibc's malloc in transparent huge pages (glibc >= 2.35; others ignore it): lavapipe's device
# memory and the validation layer's are malloc'd, and on a VM a 4 KiB page fault is dear
# (docs/stability.md, "CI coverage": the Release tests' CPU time 579 -> 510 s). Not for the
# sanitized build: ASan's allocator is not glibc's.
GLIBC_TUNABLES=glibc.malloc.hugetlb=1 ctest --test-dir build-ci -j "$jobs" -L release --output-on-failure --no-tests=error
elapsed

# cmake/Sanitizers.cmake compiles the sanitizers' options into every executable. No
# samples, no benchmarks (never run, so nothing for the sanitizers to see) and no install
# (the package test's consumer is not sanitized): build 1 has them.
echo "== the host tests, fuzz seeds and GPU rooms under AddressSanitizer + UndefinedBehaviorSanitizer (validation layer on) =="
cmake -S "$src" -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" -DVKCOLLIDE_WERROR=ON \
  -DVKCOLLIDE_SANITIZE=address,undefined -DVKCOLLIDE_BUILD_SAMPLES=OFF -DVKCOLLIDE_BUILD_BENCHMARKS=OFF -DVKCOLLIDE_INSTALL=OFF \
  "${unity[@]}" "-DVKCOLLIDE_TEST_COMPILE_OPTIONS=-O0;-fno-sanitize=undefined" >/dev/null
cmake -S "$src" -B build-host-only -G Ninja -DVKCOLLIDE_HOST_ONLY=ON -DVKCOLLIDE_WERROR=ON >/dev/null
cmake --build build-asan -j "$jobs" --target vkcollide_sanitized_suite
ctest --test-dir build-asan -j "$jobs" -L sanitized --output-on-failure --no-tests=error
elapsed
