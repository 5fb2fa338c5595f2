#!/usr/bin/env bash
# Builds tools/fuzz/fuzz_mesh_readers.cpp with clang's libFuzzer, ASan and UBSan straight
# from the reader sources (no CMake) and fuzzes all three mesh readers.
#
#   tools/fuzz/run_fuzz.sh [seconds=60] [extra libFuzzer flags...]
#
# Work folder: $FUZZ_DIR (default build/fuzz): the binaries, corpus/ (grows between
# runs; seeded from generated meshes on every run) and any crash-* / timeout-* /
# oom-* reproducers. Reproduce one with: build/fuzz/fuzz_mesh_readers <file>.
set -euo pipefail

seconds="${1:-60}"
shift || true
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
work="${FUZZ_DIR:-$root/build/fuzz}"
mkdir -p "$work/corpus"

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
    echo "run_fuzz.sh: installing clang and libclang-rt-14-dev" >&2
    apt-get install -y clang libclang-rt-14-dev >&2
fi

common=(-std=c++20 -g -O1 -fno-omit-frame-pointer -I"$root/include" -I"$root/src")
io_sources=("$root"/src/io/*.cpp)
scene_sources=("$root"/src/scene/*.cpp)

echo "run_fuzz.sh: building in $work" >&2
clang++ "${common[@]}" -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    "$root/tools/fuzz/fuzz_mesh_readers.cpp" "${io_sources[@]}" -o "$work/fuzz_mesh_readers"
clang++ "${common[@]}" "$root/tools/fuzz/write_fuzz_seeds.cpp" "${io_sources[@]}" "${scene_sources[@]}" \
    -o "$work/write_fuzz_seeds"
"$work/write_fuzz_seeds" "$work/corpus"

# -max_len: large enough for every seed; -timeout and -rss_limit_mb turn a hang or an
# allocation blow-up into a reported failure instead of a stuck run.
cd "$work"
exec ./fuzz_mesh_readers -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 "$@" corpus
