#!/usr/bin/env bash
# Quick start 2: install what is missing, build everything warning-free (-Werror) and run
# the whole suite: Catch2 tests through CTest on the Vulkan device found (lavapipe in CI)
# with the Khronos validation layer on, then host-only code under ASan + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
jobs=$(nproc)

echo "== build and test (validation layer on) =="
cmake -S . -B build-ci -G Ninja -DCMAKE_BUILD_TYPE=Release -DVKCOLLIDE_WERROR=ON >/dev/null
cmake --build build-ci -j "$jobs"
ctest --test-dir build-ci -j "$jobs" --output-on-failure --no-tests=error

echo "== host-only code under AddressSanitizer + UndefinedBehaviorSanitizer =="
san="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DVKCOLLIDE_HOST_ONLY=ON -DVKCOLLIDE_WERROR=ON \
  -DCMAKE_CXX_FLAGS="$san" -DCMAKE_EXE_LINKER_FLAGS="$san" >/dev/null
cmake --build build-asan -j "$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan -j "$jobs" --output-on-failure --no-tests=error
