#!/usr/bin/env bash
# The layers the README describes, checked on every include line of src/ (the build enforces the
# first rule too: only polarview_render sees glad's headers):
#   core      includes core only (C++17 + GLM; never GL, ImGui, GLFW);
#   pipeline  includes core and pipeline (no GL, ImGui or GLFW): its tests need no display;
#   session   the viewer without a window (state, surface cache, commands): core, pipeline, session;
#             no GL, ImGui or GLFW, so its tests need no display either;
#   render    the only layer with GL headers (glad, GL/); includes core, pipeline, render;
#   ui        ImGui and GLFW key codes, no GL; includes core, pipeline, session, ui;
#   app       everything (window, frame loop, commands), but GL only through render;
#   python    the Python module: core, pipeline, python; no GL, ImGui or GLFW.
# A violation prints FILE:LINE and the rule. Usage: bash layers.sh <polarview-exe> <repo>
set -u
repo="$2"
cd "$repo/src" || exit 1
failures=0
check() {  # layer, allowed project dirs (regex), whether GL / ImGui / GLFW headers are allowed
  local layer="$1" allowed="$2" gl="$3" imgui="$4" glfw="$5"
  while IFS= read -r hit; do
    file="${hit%%:*}"; rest="${hit#*:}"; line="${rest%%:*}"; text="${rest#*:}"
    header=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/' <<<"$text")
    case "$header" in
      glad/*|GL/*|GLES*/*)
        [ "$gl" = yes ] || { echo "FAIL: src/$file:$line: $layer includes a GL header ($header): only render may"; failures=$((failures + 1)); } ;;
      imgui*|backends/imgui*)
        [ "$imgui" = yes ] || { echo "FAIL: src/$file:$line: $layer includes ImGui ($header)"; failures=$((failures + 1)); } ;;
      GLFW/*)
        [ "$glfw" = yes ] || { echo "FAIL: src/$file:$line: $layer includes GLFW ($header)"; failures=$((failures + 1)); } ;;
      core/*|pipeline/*|session/*|render/*|ui/*|app/*|python/*)
        grep -Eq "^($allowed)/" <<<"$header" ||
          { echo "FAIL: src/$file:$line: $layer includes $header (allowed: $allowed)"; failures=$((failures + 1)); } ;;
    esac
  done < <(grep -rn --include='*.h' --include='*.cpp' -E '^[[:space:]]*#[[:space:]]*include' "$layer")
}
check core "core" no no no
check pipeline "core|pipeline" no no no
check session "core|pipeline|session" no no no
check render "core|pipeline|render" yes no yes
check ui "core|pipeline|session|ui" no yes yes
check app "core|pipeline|session|render|ui|app" no yes yes
check python "core|pipeline|python" no no no
# GLFW's header pulls in the system GL header unless GLFW_INCLUDE_NONE: defined for the whole build.
grep -q 'add_compile_definitions(GLFW_INCLUDE_NONE)' "$repo/CMakeLists.txt" ||
  { echo "FAIL: CMakeLists.txt does not define GLFW_INCLUDE_NONE"; failures=$((failures + 1)); }
# glad reaches render only (linked privately): the build itself refuses a GL include elsewhere.
grep -Eq 'target_link_libraries\(polarview_render .*PRIVATE polarview_glad' "$repo/CMakeLists.txt" ||
  { echo "FAIL: polarview_render does not link glad privately"; failures=$((failures + 1)); }
if [ "$failures" -gt 0 ]; then
  echo "layers: $failures violations"
  exit 1
fi
echo "layers: ok"
