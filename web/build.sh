#!/usr/bin/env bash
# Builds the web viewer (docs/web.md) into build-web/: index.html, polarview.js, polarview.wasm.
# Needs Debian's emscripten and Dear ImGui's sources (bash third_party/install_deps.sh); offline.
# Usage: bash web/build.sh [BUILD_DIR]   (default: build-web beside web/)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$root/build-web}"
imgui="$root/third_party/imgui-1.86"
command -v emcmake >/dev/null || { echo "web/build.sh: emscripten not installed (bash third_party/install_deps.sh)" >&2; exit 2; }
[ -f "$imgui/imgui.cpp" ] || { echo "web/build.sh: Dear ImGui sources missing at $imgui (bash third_party/install_deps.sh)" >&2; exit 2; }
# Debian's emscripten runs its JavaScript tools with the `node` on PATH; the acorn parser they need
# is Debian's node-acorn, which a node other than Debian's does not look for.
export NODE_PATH="/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}"
# Header-only host packages, linked one by one (see web/CMakeLists.txt).
mkdir -p "$out/include"
ln -sfn /usr/include/glm "$out/include/glm"
ln -sfn /usr/include/stb "$out/include/stb"
emcmake cmake -S "$root/web" -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPOLARVIEW_IMGUI_DIR="$imgui" -DPOLARVIEW_WEB_INCLUDE="$out/include" >/dev/null
cmake --build "$out"
echo "web/build.sh: $out/index.html ($(stat -c %s "$out/polarview.wasm") bytes of wasm)"
