#!/usr/bin/env bash
# Quick start 2: install what is missing, build everything warning-free (-Werror) and run
# the whole suite, in three jobs:
#   1. Release: every Catch2 test through CTest on the Vulkan device found (lavapipe in CI)
#      with the Khronos validation layer on (any message fails a test), the fuzz targets'
#      seeds replayed, the samples and the installed package;
#   2. the library, the command-line tool, the GPU tests and the world's fuzz target under
#      AddressSanitizer + UndefinedBehaviorSanitizer, run the same way (every test labelled
#      gpu: all of them, ~3 minutes of the run's time; the Vulkan driver and the layer are
#      not instrumented, tools/sanitize/ says how their leaks are told apart from ours);
#   3. the host-only code (no Vulkan) under ASan + UBSan, every test labelled host.
# About 15 minutes on two cores from a fresh clone (docs/stability.md, "CI coverage").
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

echo "== build and test (validation layer on) =="
cmake -S "$src" -B build-ci -G Ninja -DCMAKE_BUILD_TYPE=Release -DVKCOLLIDE_WERROR=ON >/dev/null
cmake --build build-ci -j "$jobs"
ctest --test-dir build-ci -j "$jobs" --output-on-failure --no-tests=error
elapsed

# Sanitizer builds: Debug (assertions on) at -O1, so that the host's share of the GPU
# tests stays fast; no samples and no package tests (their consumers are not sanitized).
# cmake/Sanitizers.cmake compiles the sanitizers' options into every executable.
san=(-G Ninja -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" -DVKCOLLIDE_WERROR=ON
     -DVKCOLLIDE_SANITIZE=address,undefined -DVKCOLLIDE_BUILD_SAMPLES=OFF -DVKCOLLIDE_INSTALL=OFF)

echo "== library, CLI and GPU tests under AddressSanitizer + UndefinedBehaviorSanitizer (validation layer on) =="
cmake -S "$src" -B build-asan-gpu "${san[@]}" >/dev/null
cmake --build build-asan-gpu -j "$jobs"
ctest --test-dir build-asan-gpu -j "$jobs" -L gpu --output-on-failure --no-tests=error
elapsed

echo "== host-only code under AddressSanitizer + UndefinedBehaviorSanitizer =="
cmake -S "$src" -B build-asan "${san[@]}" -DVKCOLLIDE_HOST_ONLY=ON >/dev/null
cmake --build build-asan -j "$jobs"
ctest --test-dir build-asan -j "$jobs" --output-on-failure --no-tests=error
elapsed
