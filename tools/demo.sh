#!/usr/bin/env bash
# Quick start 1: install what is missing, build the demo and the `vkcollide` command-line
# tool (build/tools/vkcollide), run the main job on the device found (lavapipe where no GPU
# is present).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target vkcollide_demo vkcollide_cli
./build/samples/vkcollide_demo "$@"
