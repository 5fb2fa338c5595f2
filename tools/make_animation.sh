#!/usr/bin/env bash
# Turns a sample's frames (DIR/frame_NNNN.png, in name order) into an MP4 or a GIF with
# Debian's ffmpeg, which it installs (apt-get, sudo when not root) if it is missing.
#
#   tools/make_animation.sh DIR [OUTPUT=DIR/animation.mp4] [FPS=30]
#
# OUTPUT ending in .gif makes a GIF (one palette for the whole clip), .mp4 an H.264 MP4
# that browsers play (yuv420p, even width and height).
set -euo pipefail

if [ $# -lt 1 ] || [ ! -d "$1" ]; then
    echo "usage: tools/make_animation.sh DIR [OUTPUT.mp4|OUTPUT.gif] [FPS]" >&2
    exit 2
fi
dir="$1"
out="${2:-$dir/animation.mp4}"
fps="${3:-30}"
if ! compgen -G "$dir/frame_*.png" >/dev/null; then
    echo "make_animation.sh: no frame_*.png in $dir" >&2
    exit 1
fi

if ! command -v ffmpeg >/dev/null 2>&1; then
    echo "make_animation.sh: installing ffmpeg" >&2
    sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -q >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends ffmpeg >&2
fi

# Frames may skip numbers (--png-every): read them by glob, in name order.
input=(-framerate "$fps" -pattern_type glob -i "$dir/frame_*.png")
case "$out" in
    *.gif)
        ffmpeg -y -loglevel error "${input[@]}" \
            -vf "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer" -loop 0 "$out" ;;
    *.mp4)
        ffmpeg -y -loglevel error "${input[@]}" \
            -vf "pad=ceil(iw/2)*2:ceil(ih/2)*2" -c:v libx264 -pix_fmt yuv420p -crf 20 -movflags +faststart "$out" ;;
    *)
        echo "make_animation.sh: OUTPUT must end in .mp4 or .gif" >&2
        exit 2 ;;
esac
echo "make_animation.sh: $(ls "$dir"/frame_*.png | wc -l) frames -> $out" >&2
