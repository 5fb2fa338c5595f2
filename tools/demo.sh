#!/usr/bin/env bash
# Quick start 1: install what is missing, build the demo and the `vkcollide` command-line
# tool (BUILD/tools/vkcollide), run the main job on the device found (lavapipe where no GPU
# is present).
#
#   tools/demo.sh [--build DIR] [demo options]   DIR (or VKCOLLIDE_BUILD_DIR): the build
#                                                folder, default build in the checkout; the
#                                                checkout itself is only read
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${VKCOLLIDE_BUILD_DIR:-$src/build}"
if [ "${1:-}" = "--build" ]; then
    [ $# -ge 2 ] || { echo "demo.sh: --build needs a folder" >&2; exit 2; }
    build="$2"
    shift 2
fi
bash "$src/tools/deps.sh"
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target vkcollide_demo vkcollide_cli
"$build/samples/vkcollide_demo" "$@"
