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
          emscripten chromium)  # the web viewer (web/build.sh) and its headless test (tests/web)
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
# Dear ImGui's own sources for the web viewer (web/build.sh compiles them with emscripten; Debian's
# libimgui-dev ships only the host library and headers): Debian's imgui source package, the same
# 1.86 as libimgui-dev, from the archive apt uses, checked against its .dsc checksum, unpacked beside
# this script (third_party/imgui-1.86, ignored by git).
if [ ! -f "$here/imgui-1.86/imgui.cpp" ]; then
  echo "installing: Dear ImGui 1.86 sources (Debian source package imgui 1.86+ds-1)"
  tarball="imgui_1.86+ds.orig.tar.xz"
  sha256="0dace0e8e57d298eb6e93af12dc19420cb96330832f6495c733b90aeeef11f64"
  tmp="$(mktemp -d)"
  curl -sSfL --retry 3 -o "$tmp/$tarball" "http://deb.debian.org/debian/pool/main/i/imgui/$tarball"
  echo "$sha256  $tmp/$tarball" | sha256sum -c --quiet -
  tar -xJf "$tmp/$tarball" -C "$here" imgui-1.86/imgui.cpp imgui-1.86/imgui.h imgui-1.86/imgui_draw.cpp \
    imgui-1.86/imgui_tables.cpp imgui-1.86/imgui_widgets.cpp imgui-1.86/imgui_internal.h imgui-1.86/imconfig.h \
    imgui-1.86/imstb_rectpack.h imgui-1.86/imstb_textedit.h imgui-1.86/imstb_truetype.h imgui-1.86/LICENSE.txt \
    imgui-1.86/backends/imgui_impl_glfw.cpp imgui-1.86/backends/imgui_impl_glfw.h \
    imgui-1.86/backends/imgui_impl_opengl3.cpp imgui-1.86/backends/imgui_impl_opengl3.h \
    imgui-1.86/backends/imgui_impl_opengl3_loader.h
  rm -rf "$tmp"
fi
