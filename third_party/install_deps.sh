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
          blender
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
# 1.86 as libimgui-dev, fetched by apt itself (`apt-get source`, from the mirror the system uses,
# verified by the archive's signed index, here with a private source list so the system's apt
# configuration stays as it is), its tarball checked against the pinned SHA-256 too, and unpacked
# beside this script (third_party/imgui-1.86, ignored by git).
if [ ! -f "$here/imgui-1.86/imgui.cpp" ]; then
  echo "installing: Dear ImGui 1.86 sources (Debian source package imgui 1.86+ds-1, apt-get source)"
  tarball="imgui_1.86+ds.orig.tar.xz"
  sha256="0dace0e8e57d298eb6e93af12dc19420cb96330832f6495c733b90aeeef11f64"
  tmp="$(mktemp -d)"
  chmod 755 "$tmp"  # apt's download user reads and writes there
  mirror=$(sed -n 's/^URIs: *\([^ ]*\).*/\1/p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -1)
  echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] ${mirror:-http://deb.debian.org/debian} bookworm main" \
    > "$tmp/sources.list"
  mkdir -p "$tmp/lists/partial" "$tmp/cache/archives/partial"
  apt=(apt-get -qq -o "Dir::Etc::SourceList=$tmp/sources.list" -o Dir::Etc::SourceParts=/nonexistent
       -o "Dir::State::Lists=$tmp/lists" -o "Dir::Cache=$tmp/cache")
  "${apt[@]}" update 2> /dev/null
  (cd "$tmp" && "${apt[@]}" source --download-only imgui=1.86+ds-1 > /dev/null 2>&1)
  echo "$sha256  $tmp/$tarball" | sha256sum -c --quiet -
  tar -xJf "$tmp/$tarball" -C "$here" imgui-1.86/imgui.cpp imgui-1.86/imgui.h imgui-1.86/imgui_draw.cpp \
    imgui-1.86/imgui_tables.cpp imgui-1.86/imgui_widgets.cpp imgui-1.86/imgui_internal.h imgui-1.86/imconfig.h \
    imgui-1.86/imstb_rectpack.h imgui-1.86/imstb_textedit.h imgui-1.86/imstb_truetype.h imgui-1.86/LICENSE.txt \
    imgui-1.86/backends/imgui_impl_glfw.cpp imgui-1.86/backends/imgui_impl_glfw.h \
    imgui-1.86/backends/imgui_impl_opengl3.cpp imgui-1.86/backends/imgui_impl_opengl3.h \
    imgui-1.86/backends/imgui_impl_opengl3_loader.h
  rm -rf "$tmp"
fi
