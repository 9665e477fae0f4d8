#!/usr/bin/env bash
# Watertight seams: close-ups of a valence-12 C2PS pole, levels 8, 10 and 12 from 1e-2 and 1e-3,
# from above and at 35 degrees (12 views, 600x450), show no background pixel inside the surface (a
# transparent pixel between two drawn ones, across or along a row). Before the shared edges were
# placed from the same data on both sides (shaders/common/patch_frame.glsl,
# watertightPositionFromEye) level 12 from 1e-3 had 8 such pinholes. The views draw sub-pixel ring
# sectors several to a primitive (pipeline/draw_selection.h), whose circles are cut alike on both
# sides: the level-8 close-ups also equal the full draw (--full-draw, every patch alone) but for a
# handful of pixels. (Before the draw selection a level-12 close-up took 30 s on llvmpipe, so this
# test had one view; now each takes well under a second.)
# Usage: bash render_watertight.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

"$exe" shape cap --valence 12 --links 3 -o "$work/cap.obj" > /dev/null || fail "shape cap"
target=$("$exe" pole "$work/cap.obj" --json | python3 -c 'import json, sys; print("[%.17g,%.17g,%.17g]" % tuple(json.load(sys.stdin)["poles"][0]["limit"]))')
for level in 8 10 12; do
  for distance in 1e-2 1e-3; do
    for pitch in 89 35; do
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
echo "render_watertight: $holes pinholes in 12 close-ups"
[ "${holes:-x}" = 0 ] || fail "$holes pinholes"

# The level-8 close-ups against the full draw: pixels that differ by more than 24 in a channel.
for distance in 1e-2 1e-3; do
  for pitch in 89 35; do
    "$exe" render "$work/cap.obj" --scheme c2ps --level 8 --size 600x450 --transparent --no-poles --full-draw \
      --camera "{\"target\":$target,\"distance\":$distance,\"pitch\":$pitch}" -o "$work/full.png" > /dev/null ||
      fail "render level 8 from $distance, full draw"
    count=$(python3 - "$repo/tests/support" "$work/8-$distance-$pitch.png" "$work/full.png" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from png_pixels import read_png
(a, n), (b, _) = read_png(sys.argv[2]), read_png(sys.argv[3])
print(sum(any(abs(a[y][i + c] - b[y][i + c]) > 24 for c in range(4)) for y in range(len(a)) for i in range(0, len(a[y]), n)))
PY
)
    echo "level 8 from $distance at pitch $pitch: $count pixels differ from the full draw"
    [ "${count:-x}" -le 12 ] 2> /dev/null || fail "level 8 from $distance at pitch $pitch: $count pixels differ from the full draw"
  done
done
echo "render_watertight: $failures failures"
[ $failures -eq 0 ]
