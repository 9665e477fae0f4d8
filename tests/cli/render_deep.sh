#!/usr/bin/env bash
# `polarview render` close to a deep pole: RTS and BPS at level 20 on the globe (innermost ring
# ~1e-6 of the model) seen from 1e-6 and 1e-5, and C2PS at level 10 on the default model (ring
# patches 4000 times longer than wide) seen from 1e-5. The middle of each image (below the title,
# above the colour bar) must be all surface, without speckle (a pixel unlike all 4 neighbours), and
# of one shade where nothing changes at that scale: highlight lines at 1e-6 (the normal does not
# turn), C2PS's K near its pole. Before the renderer drew relative to the eye, the near plane cut
# the surface off and the far side showed: striped, or in bands of other curvature.
# Usage: bash render_deep.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

# The limit point of the first pole, as a camera target "[x,y,z]".
pole_target() {  # file scheme
  "$exe" pole "$1" --scheme "$2" --json | python3 -c 'import json, sys; p = json.load(sys.stdin)["poles"][0]["limit"]; print("[%.17g,%.17g,%.17g]" % tuple(p))'
}

# Checks rows 15%..55% and columns 10%..90% of an RGBA PNG (below the title, above the colour bar):
# prints "uncovered speckles spread near", the pixels of alpha 0, the speckles, the largest spread
# of a channel, and the per mille of pixels within 24 of the median colour in every channel.
inspect() {  # png
  python3 - "$1" "$repo/tests/support" <<'EOF'
import sys
sys.path.insert(0, sys.argv[2])
from png_pixels import read_png
rows, _ = read_png(sys.argv[1])
height, width = len(rows), len(rows[0]) // 4
px = lambda x, y: rows[y][4 * x:4 * x + 4]
y0, y1, x0, x1 = int(0.15 * height), int(0.55 * height), int(0.1 * width), int(0.9 * width)
uncovered = speckles = 0
lo, hi = [255] * 3, [0] * 3
for y in range(y0, y1):
    for x in range(x0, x1):
        p = px(x, y)
        uncovered += p[3] == 0
        for ch in range(3):
            lo[ch], hi[ch] = min(lo[ch], p[ch]), max(hi[ch], p[ch])
        differs = lambda q: any(abs(p[ch] - q[ch]) > 24 for ch in range(3))
        speckles += all(differs(px(x + dx, y + dy)) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)))
pixels = [px(x, y) for y in range(y0, y1) for x in range(x0, x1)]
median = [sorted(p[ch] for p in pixels)[len(pixels) // 2] for ch in range(3)]
near = sum(all(abs(p[ch] - median[ch]) <= 24 for ch in range(3)) for p in pixels)
print(uncovered, speckles, max(hi[ch] - lo[ch] for ch in range(3)), 1000 * near // len(pixels))
EOF
}

globe="$repo/assets/globe.obj"
for scheme in rts bps; do
  target="$(pole_target "$globe" "$scheme")"
  for distance in 1e-5 1e-6; do
    camera="{\"target\":$target,\"distance\":$distance,\"yaw\":-60,\"pitch\":50}"
    for shade in gaussian highlight; do
      png="$work/$scheme-$distance-$shade.png"
      if ! "$exe" render "$globe" -o "$png" --scheme "$scheme" --level 20 --shade "$shade" --colormap magnitude \
          --range 2 --size 320x320 --transparent --no-poles --camera "$camera" > /dev/null 2> "$work/err.txt"; then
        fail "$scheme level 20 from $distance ($shade): $(cat "$work/err.txt")"
        continue
      fi
      read -r uncovered speckles spread near <<< "$(inspect "$png")"
      [ "$uncovered" = 0 ] || fail "$scheme level 20 from $distance ($shade): $uncovered uncovered pixels"
      # From 1e-5 the cap's rim, where its K meets the ring's with a jump (the cap is C1 there), is a
      # band a pixel or two wide; K is checked for speckle from 1e-6, where the cap fills the view.
      if [ "$shade" = highlight ] || [ "$distance" = 1e-6 ]; then
        [ "$speckles" = 0 ] || fail "$scheme level 20 from $distance ($shade): $speckles speckles"
      fi
      if [ "$shade" = highlight ] && [ "$distance" = 1e-6 ] && [ "$spread" -gt 12 ]; then
        fail "$scheme level 20 from $distance: highlight lines vary by $spread (striped: not the surface at the pole)"
      fi
    done
  done
done

# C2PS level 10: its deepest ring patches are 1e-3 long and 4000 times thinner.
model="$repo/assets/default.obj"
target="$(pole_target "$model" c2ps)"
png="$work/c2ps.png"
if "$exe" render "$model" -o "$png" --scheme c2ps --level 10 --shade gaussian --colormap magnitude --range 1 \
    --size 320x320 --transparent --no-poles --camera "{\"target\":$target,\"distance\":1e-5,\"yaw\":-60,\"pitch\":50}" \
    > /dev/null 2> "$work/err.txt"; then
  read -r uncovered speckles spread near <<< "$(inspect "$png")"
  [ "$uncovered" = 0 ] || fail "c2ps level 10 from 1e-5: $uncovered uncovered pixels"
  # The rings' 1536-fold valence leaves sub-pixel slivers between patches: a few pinholes show.
  [ "$speckles" -le 8 ] || fail "c2ps level 10 from 1e-5: $speckles speckles"
  # K is 0.437 at the pole and hardly changes over the 6e-6 in view: one colour.
  [ "$near" -ge 995 ] || fail "c2ps level 10 from 1e-5: only $near per mille of the pixels near the median colour"
else
  fail "c2ps level 10 from 1e-5: $(cat "$work/err.txt")"
fi

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "render_deep: all checks passed"
