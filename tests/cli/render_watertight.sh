#!/usr/bin/env bash
# Watertight seams: a close-up of a valence-12 C2PS pole at level 12 from 1e-3, from above, where
# the rings' sectors are a tenth of a pixel wide, shows no background pixel inside the surface (a
# transparent pixel between two drawn ones, across or along a row). Before the shared edges were
# placed from the same data on both sides (shaders/common/patch_frame.glsl,
# watertightPositionFromEye) it had 8 such pinholes at 600x450 (levels 10 and 12 from 1e-2 and 1e-3,
# two pitches, 8 views: 17; a close-up at level 12 takes seconds on llvmpipe, so one here).
# Usage: bash render_watertight.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

"$exe" shape cap --valence 12 --links 3 -o "$work/cap.obj" > /dev/null || fail "shape cap"
target=$("$exe" pole "$work/cap.obj" --json | python3 -c 'import json, sys; print("[%.17g,%.17g,%.17g]" % tuple(json.load(sys.stdin)["poles"][0]["limit"]))')
for level in 12; do
  for distance in 1e-3; do
    for pitch in 89; do
      "$exe" render "$work/cap.obj" --scheme c2ps --level "$level" --size 600x450 --transparent --no-poles \
        --camera "{\"target\":$target,\"distance\":$distance,\"pitch\":$pitch}" -o "$work/$level-$distance-$pitch.png" > /dev/null ||
        fail "render level $level from $distance"
    done
  done
done
# Rows above the colour bar (75%): transparent pixels with drawn ones on both sides.
holes=$(python3 - "$repo/tests/support" "$work"/*.png <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from png_pixels import read_png
total = 0
for path in sys.argv[2:]:
    rows, n = read_png(path)
    alpha = lambda x, y: rows[y][n * x + 3]
    found = [(x, y) for y in range(1, int(0.75 * len(rows))) for x in range(1, len(rows[y]) // n - 1)
             if alpha(x, y) == 0 and ((alpha(x - 1, y) and alpha(x + 1, y)) or (alpha(x, y - 1) and alpha(x, y + 1)))]
    if found: print(path.split("/")[-1], len(found), found[:5], file=sys.stderr)
    total += len(found)
print(total)
PY
)
echo "render_watertight: $holes pinholes in a close-up"
[ "${holes:-x}" = 0 ] || fail "$holes pinholes"
echo "render_watertight: $failures failures"
[ $failures -eq 0 ]
