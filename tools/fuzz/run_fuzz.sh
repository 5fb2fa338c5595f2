#!/usr/bin/env bash
# Fuzzes a target under clang's libFuzzer with ASan and UBSan for a given time.
#
#   tools/fuzz/run_fuzz.sh [seconds=60] [readers|world] [extra libFuzzer flags...]
#
# readers: tools/fuzz/fuzz_mesh_readers.cpp, all three mesh readers on every input, built
#          straight from the reader sources (no CMake, seconds to build).
# world:   tools/fuzz/fuzz_world.cpp, programs of CollisionWorld calls (world_program.hpp)
#          on the Vulkan device found (lavapipe here) with the validation layer on, built
#          with CMake (-DVKCOLLIDE_SANITIZE=address,undefined -DVKCOLLIDE_FUZZ=ON: the
#          library instrumented too; a few minutes on two cores the first time).
#          VKCOLLIDE_FUZZ_VALIDATION=0 turns the layer off (faster, sees less);
#          VKCOLLIDE_FUZZ_VERBOSE=1 prints every call (to read a finding).
#
# Work folder: $FUZZ_DIR (default build/fuzz): the binaries (world: world-build/), the
# corpora (corpus/, world-corpus/: they grow between runs and are seeded again on every
# run) and any crash-* / timeout-* / oom-* reproducers. Reproduce one with the binary and
# the file: build/fuzz/fuzz_mesh_readers <file>, build/fuzz/world-build/tools/fuzz/vkcollide_fuzz_world <file>.
# Once fixed, copy it into tools/fuzz/regressions/<target>/: CTest replays those.
set -euo pipefail

seconds="${1:-60}"
shift || true
target="readers"
if [[ $# -gt 0 && ( "$1" == "readers" || "$1" == "world" ) ]]; then
    target="$1"
    shift
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
work="${FUZZ_DIR:-$root/build/fuzz}"
mkdir -p "$work"

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
    echo "run_fuzz.sh: installing clang and libclang-rt-14-dev" >&2
    apt-get install -y clang libclang-rt-14-dev >&2
fi

# -timeout and -rss_limit_mb turn a hang or an allocation blow-up into a reported failure
# instead of a stuck run.
if [[ "$target" == "readers" ]]; then
    mkdir -p "$work/corpus"
    common=(-std=c++20 -g -O1 -fno-omit-frame-pointer -I"$root/include" -I"$root/src")
    io_sources=("$root"/src/io/*.cpp)
    scene_sources=("$root"/src/scene/*.cpp)
    echo "run_fuzz.sh: building the readers' target in $work" >&2
    clang++ "${common[@]}" -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
        "$root/tools/fuzz/fuzz_mesh_readers.cpp" "${io_sources[@]}" -o "$work/fuzz_mesh_readers"
    clang++ "${common[@]}" "$root/tools/fuzz/write_fuzz_seeds.cpp" "${io_sources[@]}" "${scene_sources[@]}" \
        -o "$work/write_fuzz_seeds"
    "$work/write_fuzz_seeds" "$work/corpus"
    cd "$work"
    # -max_len: large enough for every seed.
    exec ./fuzz_mesh_readers -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 "$@" corpus
fi

build="$work/world-build"
echo "run_fuzz.sh: building the world's target in $build" >&2
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DVKCOLLIDE_SANITIZE=address,undefined \
    -DVKCOLLIDE_FUZZ=ON -DVKCOLLIDE_BUILD_SAMPLES=OFF -DVKCOLLIDE_INSTALL=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target vkcollide_fuzz_world vkcollide_write_world_seeds
"$build/tools/fuzz/vkcollide_write_world_seeds" "$work/world-corpus"
cd "$work"
# -max_len: a program of kMaxOps calls with the largest meshes fits in 1 KiB. An input
# runs at most 10 detections of tiny meshes: well under a second, unless it hangs.
exec "$build/tools/fuzz/vkcollide_fuzz_world" -max_total_time="$seconds" -max_len=1024 -timeout=60 \
    -rss_limit_mb=4096 -print_final_stats=1 "$@" world-corpus
