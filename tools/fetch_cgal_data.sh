#!/usr/bin/env bash
# Extracts the test meshes we use from Debian's libcgal-demo package into a folder.
#
#   tools/fetch_cgal_data.sh [dest=data/cgal]
#
# libcgal-demo ships CGAL's sample data as /usr/share/doc/libcgal-dev/data.tar.gz; the
# meshes sit under data/meshes/ in it. They are copied flat into dest
# (data/meshes/bunny00.off -> dest/bunny00.off). docs/datasets.md lists them with their
# triangle counts. dest is git-ignored: never commit the meshes.
#
# Nothing is installed: where libcgal-demo is not installed already, its .deb alone is
# downloaded (`apt-get download`, no root, none of its dependencies: Qt and some 47 other
# packages) into a cache folder, VKCOLLIDE_CACHE (default ~/.cache/vkcollide), and unpacked
# there with `dpkg-deb -x`. The package lists must be current (`apt-get update`).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${1:-$root/data/cgal}"

# Closed, consistently oriented meshes first (collision tests), then a few open ones
# and the PLY files (reader coverage).
meshes=(
    armadillo.off bunny00.off camel.off cow.off eight.off elephant.off fandisk.off
    knot1.off man.off refined_elephant.off triceratops.off sphere.off
    ChineseDragon-10kv.off mushroom.off
    sphere.ply colored_tetra.ply
)

if dpkg-query -W -f='${Status}' libcgal-demo 2>/dev/null | grep -q "install ok installed"; then
    archive="$(dpkg -L libcgal-demo | grep -E '/data\.tar\.gz$' | head -n 1)"
else
    cache="${VKCOLLIDE_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/vkcollide}/libcgal-demo"
    mkdir -p "$cache"
    if ! ls "$cache"/libcgal-demo_*.deb >/dev/null 2>&1; then
        echo "fetch_cgal_data.sh: downloading libcgal-demo's .deb into $cache (nothing is installed)" >&2
        (cd "$cache" && apt-get download libcgal-demo >&2) || {
            echo "fetch_cgal_data.sh: apt-get download libcgal-demo failed (are the package lists current? apt-get update)" >&2
            exit 1
        }
    fi
    deb="$(ls "$cache"/libcgal-demo_*.deb | head -n 1)"
    [ -d "$cache/root" ] || dpkg-deb -x "$deb" "$cache/root"
    archive="$(find "$cache/root" -name data.tar.gz -path '*libcgal*' | head -n 1)"
fi
if [ -z "$archive" ] || [ ! -f "$archive" ]; then
    echo "fetch_cgal_data.sh: libcgal-demo has no data.tar.gz" >&2
    exit 1
fi

mkdir -p "$dest"
members=()
for mesh in "${meshes[@]}"; do members+=("data/meshes/$mesh"); done
tar -xzf "$archive" -C "$dest" --strip-components=2 "${members[@]}"
echo "fetch_cgal_data.sh: ${#meshes[@]} meshes from $archive in $dest" >&2
