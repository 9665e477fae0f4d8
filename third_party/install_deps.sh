#!/usr/bin/env bash
# Installs the Debian 12 packages polarview builds and tests with, only those that are missing.
# Everything comes from Debian: nothing is vendored or downloaded from elsewhere.
set -euo pipefail
packages=(cmake ninja-build pkg-config g++
          libglfw3-dev libglm-dev libimgui-dev python3-glad libtinyobjloader-dev doctest-dev libstb-dev
          libosd-dev
          clang-14 libclang-rt-14-dev
          xvfb xauth mesa-utils libgl1-mesa-dri
          occt-draw libocct-draw-dev
          pybind11-dev python3-pybind11 python3-dev python3-pip python3-venv python3-setuptools python3-wheel python3-numpy python3-scipy python3-pytest python3-matplotlib
          python3-meshio
          blender)
missing=()
# npm (for the glTF validator below): the image's Node.js carries it; Debian's npm where it does not.
command -v npm >/dev/null || packages+=(npm)
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The Khronos glTF validator (the glb export's test oracle) from npm, beside this script
# (third_party/node, ignored by git); the tests read it from there.
here="$(cd "$(dirname "$0")" && pwd)"
if [ ! -f "$here/node/node_modules/gltf-validator/package.json" ]; then
  echo "installing: gltf-validator (npm)"
  npm install --silent --no-save --no-audit --no-fund --prefix "$here/node" gltf-validator@2.0.0-dev.3.10 >/dev/null
fi
