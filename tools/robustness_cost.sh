#!/usr/bin/env bash
# What robustBufferAccess (and robustBufferAccess2), which Context::create turns on as a
# second line of defence, costs a detection: the same scenes with and without, on the
# device found (VKCOLLIDE_DEVICE picks one), median of K frames after a warm-up frame.
#
#   tools/robustness_cost.sh [build dir=build] [frames=20]
#
# Needs build/tools/vkcollide (tools/demo.sh or `cmake --build build --target vkcollide_cli`).
# The scenes are written here (no data download): two overlapping UV spheres and a stack
# of four at three tessellations. Prints one table row per scene and setting.
set -euo pipefail
build="${1:-build}"
frames="${2:-20}"
cli="$build/tools/vkcollide"
[ -x "$cli" ] || { echo "robustness_cost.sh: $cli not found; build vkcollide_cli first" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# sphere <name> <cx> <cy> <cz> <segments> <rings>: one `o` group, vertices numbered from $base.
sphere() {
    awk -v name="$1" -v cx="$2" -v cy="$3" -v cz="$4" -v seg="$5" -v rings="$6" -v base="$7" 'BEGIN {
        pi = atan2(0, -1); print "o " name
        for (r = 0; r <= rings; ++r) for (s = 0; s < seg; ++s) {
            t = pi * r / rings; p = 2 * pi * s / seg
            printf "v %.7f %.7f %.7f\n", cx + sin(t) * cos(p), cy + cos(t), cz + sin(t) * sin(p)
        }
        for (r = 0; r < rings; ++r) for (s = 0; s < seg; ++s) {
            a = base + r * seg + s; b = base + r * seg + (s + 1) % seg
            c = a + seg; d = b + seg
            if (r > 0) printf "f %d %d %d\n", a, b, d
            if (r < rings - 1) printf "f %d %d %d\n", a, d, c
        }
    }'
}

scene() {  # scene <file> <segments> <rings> <count>
    local file="$1" seg="$2" rings="$3" count="$4" base=1 i
    : > "$file"
    for ((i = 0; i < count; ++i)); do
        sphere "s$i" "$(awk -v i="$i" 'BEGIN { print 1.2 * i }')" 0 0 "$seg" "$rings" "$base" >> "$file"
        base=$((base + (rings + 1) * seg))
    done
}

scene "$work/two-2k.obj" 48 24 2
scene "$work/two-130k.obj" 360 180 2
scene "$work/four-520k.obj" 512 256 4

printf "%-16s %-10s %10s %12s %12s %10s\n" scene robust total_ms sampling_ms narrow_ms pairs
for f in "$work"/*.obj; do
    for mode in on off; do
        flag=""; [ "$mode" = off ] && flag="--no-robust-access"
        times=()
        for ((k = 0; k <= frames; ++k)); do
            "$cli" detect "$f" --no-self-collision --frames 2 --stats "$work/s.json" $flag > /dev/null
            ((k == 0)) && continue  # warm-up (first process: driver caches)
            times+=("$(awk -F': ' '/"total_ms"/ { gsub(",", "", $2); print $2 }' "$work/s.json")")
        done
        median=$(printf "%s\n" "${times[@]}" | sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }')
        sampling=$(awk -F': ' '/"sampling_ms"/ { gsub(",", "", $2); print $2 }' "$work/s.json")
        narrow=$(awk -F': ' '/"narrow_ms"/ { gsub(",", "", $2); print $2 }' "$work/s.json")
        pairs=$(awk -F': ' '/"pairs"/ { gsub(",", "", $2); print $2 }' "$work/s.json")
        printf "%-16s %-10s %10.3f %12.3f %12.3f %10s\n" "$(basename "$f" .obj)" "$mode" "$median" "$sampling" "$narrow" "$pairs"
    done
done
