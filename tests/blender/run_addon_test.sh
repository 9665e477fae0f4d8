#!/usr/bin/env bash
# ctest blender.addon: runs Debian's Blender headless on the add-on zip (tests/blender/addon_test.py)
# against the CLI built beside it. Exit 77 (ctest's SKIP_RETURN_CODE) where there is no Blender.
# Usage: run_addon_test.sh ZIP POLARVIEW_CLI SOURCE_DIR    (BLENDER=... picks the executable)
set -euo pipefail
zip="$1" cli="$2" source="$3"
blender="${BLENDER:-$(command -v blender || true)}"
if [ -z "$blender" ] || [ ! -x "$blender" ]; then
  echo "SKIP: Blender not found (install Debian's blender, or set BLENDER=/path/to/blender)"
  exit 77
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The add-on is installed into a throw-away user scripts folder, never the user's own.
export BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config"
run() {
  "$blender" -b --factory-startup -noaudio --python-exit-code 1 -P "$source/tests/blender/addon_test.py" -- \
    --zip "$1" --cli "$cli" --source "$source" --work "$work" --case "$2"
}
run "$zip" surfaces
# An add-on whose extension is missing (the test removes it from a copy) must load, say why, and
# refuse politely.
rm -rf "$work/scripts"
run "$zip" broken
