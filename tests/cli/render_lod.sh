#!/usr/bin/env bash
# Level of detail (pipeline/level_of_detail.h): a view draws the shallowest level whose caps or end
# caps are below 3 pixels at every feature. On the default model at the default camera C2PS level 12
# (246,237 patches) draws level 7 or so, RTS and Catmull-Clark level 24 a level below 10, and each
# picture equals the full draw (--full-draw) but for a few pixels (the cap at a pole, 3 pixels across:
# RTS's, which has a curvature of its own, differs on its rim); close to the pole the deepest
# level is drawn (its rings are then many pixels wide). Before, level 12 drew every patch: a frame
# cost 0.8 s against 30 ms at level 6 here.
# Usage: bash render_lod.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures
model="$repo/assets/default.obj"

# Pixels of two pictures that differ by more than 24 in a channel.
differing() {  # png png
  python3 - "$1" "$2" "$repo/tests/support" <<'PY'
import sys
sys.path.insert(0, sys.argv[3])
from png_pixels import read_png
(a, n), (b, _) = read_png(sys.argv[1]), read_png(sys.argv[2])
print(sum(any(abs(a[y][i + c] - b[y][i + c]) > 24 for c in range(3)) for y in range(len(a)) for i in range(0, len(a[y]), n)))
PY
}
drawn_level() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["drawn_levels"][0])' "$1"; }

for case in "c2ps 12 9" "rts 24 10" "cc 24 10"; do
  read -r scheme level most <<< "$case"
  "$exe" render "$model" --scheme "$scheme" --level "$level" --size 600x400 --time 1 -o "$work/lod.png" > "$work/lod.json" ||
    fail "$scheme $level: render"
  "$exe" render "$model" --scheme "$scheme" --level "$level" --size 600x400 --full-draw -o "$work/full.png" > /dev/null ||
    fail "$scheme $level: render --full-draw"
  drawn=$(drawn_level "$work/lod.json")
  [ "${drawn:-99}" -le "$most" ] 2> /dev/null || fail "$scheme $level: drew level $drawn at the default camera (at most $most expected)"
  count=$(differing "$work/lod.png" "$work/full.png")
  echo "$scheme level $level: drawn at level $drawn, $count pixels differ from the full draw"
  [ "${count:-x}" -le 12 ] 2> /dev/null || fail "$scheme $level: $count pixels differ from the full draw"
done

# Close to the pole the rings are many pixels wide: level 12 itself is drawn.
target=$("$exe" pole "$model" --json | python3 -c 'import json, sys; print("[%.17g,%.17g,%.17g]" % tuple(json.load(sys.stdin)["poles"][0]["limit"]))')
"$exe" render "$model" --scheme c2ps --level 12 --size 400x300 --time 1 -o "$work/close.png" \
  --camera "{\"target\":$target,\"distance\":1e-3,\"pitch\":60}" > "$work/close.json" || fail "close-up: render"
[ "$(drawn_level "$work/close.json")" = 12 ] || fail "close-up of the pole: drew level $(drawn_level "$work/close.json"), not 12"

echo "render_lod: $failures failures"
[ $failures -eq 0 ]
