#!/usr/bin/env bash
# `render` draws every scale the OBJ reader accepts (coordinates up to 1e150): the globe scaled by
# 1e-150, 1e-80, 1e-10, 1e15, 1e40 and 1e150 gives the picture of the globe itself (the renderer
# works in a power-of-two unit near the model's size, the curvature samples and the colour range in
# double; its colours depend on the automatic range, so that is checked too), and a typed range of
# 3 / s^2 gives the colours of 3 on the globe. Before: a blank picture with exit 0 from 1e-10 down and
# from 1e40 up, and a range of +-1e-30 (labels 0, one colour) at 1e15.
# Usage: bash render_scales.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

"$exe" shape globe -o "$work/globe.obj" > /dev/null || fail "shape globe"
render() {  # obj png [range]
  "$exe" render "$1" -o "$2" --scheme c2ps --level 3 --size 320x240 ${3:+--range "$3"} > /dev/null 2> "$work/err.txt" ||
    fail "render $1: $(cat "$work/err.txt")"
}
# Pixels above the colour bar (rows 0..70%) of two pictures that differ by more than 24.
differing() {  # png png
  python3 - "$1" "$2" "$repo/tests/support" <<'PY'
import sys
sys.path.insert(0, sys.argv[3])
from png_pixels import read_png
(a, n), (b, _) = read_png(sys.argv[1]), read_png(sys.argv[2])
rows = int(0.7 * len(a))
print(sum(any(abs(a[y][i + c] - b[y][i + c]) > 24 for c in range(3))
          for y in range(rows) for i in range(0, len(a[y]), n)))
PY
}
render "$work/globe.obj" "$work/1.png"
render "$work/globe.obj" "$work/1-typed.png" 3
for scale in 1e-150 1e-80 1e-10 1e15 1e40 1e150; do
  awk -v s="$scale" '/^v /{printf "v %.17g %.17g %.17g\n", $2 * s, $3 * s, $4 * s; next} {print}' \
    "$work/globe.obj" > "$work/globe$scale.obj"
  # The automatic colour range (the surface's colours depend on it) and a typed one, K's 3 / s^2.
  render "$work/globe$scale.obj" "$work/$scale.png"
  render "$work/globe$scale.obj" "$work/$scale-typed.png" "$(python3 -c "print(repr(3.0 / ($scale * $scale)))")"
  for kind in "" -typed; do
    count=$(differing "$work/1$kind.png" "$work/$scale$kind.png")
    [ "${count:-x}" -le 20 ] 2> /dev/null || fail "scale $scale$kind: $count pixels differ from the unscaled globe's picture"
  done
done

# Below 1e-150 curvature (1 / size^2) leaves double's range: refused with a line, no picture.
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2 * 1e-200, $3 * 1e-200, $4 * 1e-200; next} {print}' \
  "$work/globe.obj" > "$work/tiny.obj"
if "$exe" render "$work/tiny.obj" -o "$work/tiny.png" > /dev/null 2> "$work/err.txt"; then
  fail "a globe of 1e-200 was drawn (its K is past double's range)"
fi
grep -q "tiny.obj: the model spans 2e-200, below 1e-150" "$work/err.txt" || fail "tiny model: $(cat "$work/err.txt")"
[ ! -e "$work/tiny.png" ] || fail "a refused model left a picture"

echo "render_scales: $failures failures"
[ $failures -eq 0 ]
