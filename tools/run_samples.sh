#!/usr/bin/env bash
# Runs the samples of docs/samples.md at full size, headless, on the device found
# (VKCOLLIDE_DEVICE=<name> picks one), and writes under OUT one folder per run (its PNG
# frames, frames.csv and log) and OUT/summary.md: each run's Table 1 rows (mean and max
# over the frames after the first) beside the paper's.
#
#   tools/run_samples.sh [--build DIR] [--out DIR] [--size WxH] [--png-every N] [--pack DIR] [--only RUN] [-- ARGS...]
#   tools/run_samples.sh [--build DIR] --bundle DIR
#
#   --build DIR     the build folder (default: build in the checkout); the CGAL meshes are
#                   fetched into DIR/data/cgal, so a read-only checkout works with a build
#                   folder elsewhere
#   --out DIR       default samples-out (relative to the current folder)
#   --size WxH      image size, default 640x400
#   --png-every N   keep every N-th frame as PNG, default 2
#   --only RUN      one run: deformable_bunnies, deformable_horses, creatures, rigid_bunnies,
#                   dragon or cloth
#   --pack DIR      also write DIR/<run>.tar.gz (frames.csv, log, frames) and DIR/summary.md:
#                   seven files, for a machine that returns only a few
#   -- ARGS         passed to every sample (e.g. --backend compute, --resolution 1024)
#   --bundle DIR    (here, after a build) copy the sample programs, the libraries they need
#                   beyond a bare system (libvulkan, libpng, meshoptimizer), the CGAL meshes
#                   they read and this script into DIR, to carry to a GPU machine; there,
#                   run DIR/run_samples.sh (it uses the programs beside it).
#
# In the repository it installs what is missing (tools/deps.sh), fetches the CGAL meshes
# (tools/fetch_cgal_data.sh, into the build folder) and builds the samples (Release, in the
# build folder). Nothing is written into the checkout.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
programs=(vkcollide_deformable vkcollide_creatures vkcollide_rigid_bunnies vkcollide_dragon vkcollide_cloth)
meshes=(bunny00.off camel.off elephant.off ChineseDragon-10kv.off)

out="samples-out" size="640x400" every=2 pack="" only="" bundle="" build=""
extra=()
while [ $# -gt 0 ]; do
    case "$1" in
        --build) build="$2"; shift 2 ;;
        --out) out="$2"; shift 2 ;;
        --size) size="$2"; shift 2 ;;
        --png-every) every="$2"; shift 2 ;;
        --pack) pack="$2"; shift 2 ;;
        --only) only="$2"; shift 2 ;;
        --bundle) bundle="$2"; shift 2 ;;
        --) shift; extra=("$@"); break ;;
        *) echo "run_samples.sh: unknown argument $1 (see the comment at the top)" >&2; exit 2 ;;
    esac
done

if [ -x "$here/vkcollide_cloth" ]; then
    # A bundle: programs, libraries and meshes beside this script.
    bin="$here" data="$here/data"
    export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
else
    root="$(cd "$here/.." && pwd)"
    build="${build:-$root/build}"
    mkdir -p "$build"
    build="$(cd "$build" && pwd)"
    bash "$root/tools/deps.sh"
    bash "$root/tools/fetch_cgal_data.sh" "$build/data/cgal" >/dev/null
    [ -f "$build/build.ninja" ] || cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$build" --target vkcollide_samples
    bin="$build/samples" data="$build/data/cgal"
fi

if [ -n "$bundle" ]; then
    mkdir -p "$bundle/lib" "$bundle/data"
    for p in "${programs[@]}"; do cp "$bin/$p" "$bundle/"; done
    # The shared libraries a bare machine may lack (the C++ runtime and libc it has).
    ldd "$bin/vkcollide_deformable" "$bin/vkcollide_creatures" | awk '/=> \// {print $3}' | sort -u |
        grep -E 'libvulkan|libpng|libmeshoptimizer|libz\.' | while read -r lib; do cp -L "$lib" "$bundle/lib/"; done
    for m in "${meshes[@]}"; do cp "$data/$m" "$bundle/data/"; done
    cp "${BASH_SOURCE[0]}" "$bundle/run_samples.sh"
    echo "run_samples.sh: bundle in $bundle ($(du -sh "$bundle" | cut -f1)); run $bundle/run_samples.sh there" >&2
    exit 0
fi

# run name | program | its arguments | the paper's Table 1 row (NVIDIA 7800 GTX, 2006)
runs=(
    "deformable_bunnies|vkcollide_deformable|--bodies bunnies|defo bunnies 12K, 0.2K rays, 0.4K downl., 0.2K pot., 0.4K tests, 0.1K pos., 3+1+1 = 5 ms"
    "deformable_horses|vkcollide_deformable|--bodies horses|defo horses 32K, 21K rays, 13K downl., 4.3K pot., 9.0K tests, 3.7K pos., 5+4+24 = 33 ms"
    "creatures|vkcollide_creatures||art. creatures 320K, 0.3K rays, 1.0K downl., 0.4K pot., 1.5K tests, 0.2K pos., 17+6+1 = 24 ms"
    "rigid_bunnies|vkcollide_rigid_bunnies||rigid bunnies 500K, 2.8K rays, 12K downl., 4.4K pot., 7.7K tests, 1.5K pos., 56+18+21 = 95 ms"
    "dragon|vkcollide_dragon||dragon 800K, 7.7K rays, 54K downl., 7.5K pot., 6.6K tests, 1.5K pos., 53+32+139 = 224 ms"
    "cloth|vkcollide_cloth||cloth (section 8.2) 2K, up to 2K tests, up to 300 pairs, 5 ms mean / 12 ms max"
)

mkdir -p "$out"
summary="$out/summary.md"
{
    echo "# vkcollide samples at full size"
    echo
    echo "Run $(date -u +%Y-%m-%dT%H:%MZ), \`run_samples.sh --size $size --png-every $every ${extra[*]:-}\`."
    echo "Columns: # tri's, # coll. rays, # tri's downl., # pot. coll. tri's, # tri-tri tests, # pos. tests,"
    echo "GPU (the method's GPU stages: peeling sampling + merging + separation, reliable front + footprints +"
    echo "pairing + filtering), Reduce (packing + readback), CPU (narrow phase), Overall (ms)."
    echo
} >"$summary"
width="${size%x*}" height="${size#*x}"
for entry in "${runs[@]}"; do
    IFS='|' read -r name program args paper <<<"$entry"
    [ -z "$only" ] || [ "$only" = "$name" ] || continue
    dir="$out/$name"
    rm -rf "$dir"
    mkdir -p "$dir"
    echo "== $name: $program $args" >&2
    # shellcheck disable=SC2086  # $args holds several arguments
    if ! "$bin/$program" $args --out "$dir" --width "$width" --height "$height" --png-every "$every" --data "$data" --quiet \
        "${extra[@]}" >"$dir/log.txt" 2>"$dir/stderr.txt"; then
        echo "run_samples.sh: $name failed (see $dir/stderr.txt)" >&2
        tail -n 5 "$dir/stderr.txt" >&2
    fi
    {
        echo "## $name"
        echo
        echo '```'
        grep -E '^(device|settings|scene|dragon|bunny|camel|elephant):' "$dir/log.txt" || true
        sed -n '/^Table 1/,$p' "$dir/log.txt"
        echo "paper: $paper"
        echo '```'
        echo
    } >>"$summary"
    tail -n 4 "$dir/log.txt" >&2
done
echo "run_samples.sh: summary in $summary" >&2

if [ -n "$pack" ]; then
    mkdir -p "$pack"
    cp "$summary" "$pack/"
    for dir in "$out"/*/; do
        name="$(basename "$dir")"
        tar -czf "$pack/$name.tar.gz" -C "$out" "$name"
    done
    ls -la "$pack" >&2
fi
