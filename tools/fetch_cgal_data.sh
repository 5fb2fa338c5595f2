#!/usr/bin/env bash
# Extracts the test meshes we use from Debian's libcgal-demo package into a folder.
#
#   tools/fetch_cgal_data.sh [dest=data/cgal]
#
# libcgal-demo ships CGAL's sample data as /usr/share/doc/libcgal-dev/data.tar.gz
# (listed by `dpkg -L libcgal-demo`); the meshes sit under data/meshes/ in it. They are
# copied flat into dest (data/meshes/bunny00.off -> dest/bunny00.off). docs/datasets.md
# lists them with their triangle counts. dest is git-ignored: never commit the meshes.
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

if ! dpkg-query -W -f='${Status}' libcgal-demo 2>/dev/null | grep -q "install ok installed"; then
    echo "fetch_cgal_data.sh: installing libcgal-demo" >&2
    if [ "$(id -u)" -eq 0 ]; then
        apt-get install -y libcgal-demo >&2
    else
        sudo apt-get install -y libcgal-demo >&2
    fi
fi

archive="$(dpkg -L libcgal-demo | grep -E '/data\.tar\.gz$' | head -n 1)"
if [ -z "$archive" ] || [ ! -f "$archive" ]; then
    echo "fetch_cgal_data.sh: libcgal-demo has no data.tar.gz (dpkg -L libcgal-demo)" >&2
    exit 1
fi

mkdir -p "$dest"
members=()
for mesh in "${meshes[@]}"; do members+=("data/meshes/$mesh"); done
tar -xzf "$archive" -C "$dest" --strip-components=2 "${members[@]}"
echo "fetch_cgal_data.sh: ${#meshes[@]} meshes from $archive in $dest" >&2
