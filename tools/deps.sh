#!/usr/bin/env bash
# Installs what vkcollide needs from Debian's archive, only if something is missing.
set -euo pipefail
packages=(cmake ninja-build ccache g++ clang libclang-rt-14-dev libvulkan-dev glslang-tools spirv-tools libeigen3-dev libgmp-dev
          catch2 mesa-vulkan-drivers vulkan-validationlayers vulkan-tools libpng-dev libmeshoptimizer-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "vkcollide: installing ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
