#!/usr/bin/env bash
# Installs the Debian 12 packages polarview builds and tests with, only those that are missing.
# Everything comes from Debian: nothing is vendored or downloaded from elsewhere.
set -euo pipefail
packages=(cmake ninja-build pkg-config g++
          libglfw3-dev libglm-dev libimgui-dev python3-glad libtinyobjloader-dev doctest-dev libstb-dev
          libosd-dev
          clang-14 libclang-rt-14-dev
          xvfb xauth mesa-utils libgl1-mesa-dri)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "installing: ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
