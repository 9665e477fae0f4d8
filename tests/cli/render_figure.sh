#!/usr/bin/env bash
# `polarview figure` and per-view shading in `polarview render`. Figure 1 must draw lit eigensplines
# under black nets in each of its columns. Figure 13 (the shape gallery: five
# valence-12 caps; columns input net, twice subdivided net, Gaussian curvature, highlight lines)
# must be a full-colour RGB PNG 1200 wide (no 256-colour palette: it banded the shading) whose
# curvature column holds both signs of the paper map (blue saddles, red paraboloid and flat point
# ring) and its green band at zero (the monkey saddle's and flat point's centres) in thousands of
# colours, whose highlight column is black and white stripes without map colours, and whose net
# columns are dark lines over a lit surface, without map colours. Figure 11's input (a valence-6
# cone) must show what the figure claims: with the uniform first step dK/dr changes sign along the
# spokes less often than under C2PS applied directly (`pole --rings`' spoke_sign_changes). `render --shade gaussian,highlight` must colour the first
# view only; mismatched shade lists and unknown figures are usage errors (exit 2).
# Usage: bash render_figure.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

# Prints "width height type" and, per column band [x0, x1) given as arguments "x0:x1", the pixels
# that are map blue, map red, map green, dark (stripes: under 100, unlike the background, the most
# common colour) and light (lit stripes, net lines: over 180), of an 8-bit
# PNG (RGB, RGBA or indexed), counting only the rows of views: those where the grey line that
# separates the first two views runs (at x = the first band's end), not the strips of colour bar and
# legend under them.
count_colours() {  # png band...
  python3 - "$repo/tests/support" "$@" <<'EOF'
import sys
sys.path.insert(0, sys.argv[1])
from png_pixels import read_png
del sys.argv[1]
rows, n, colour = read_png(sys.argv[1], with_type=True)
height, width = len(rows), len(rows[0]) // n
def pixel(x, y):
    return tuple(rows[y][n * x:n * x + 3])
separator = int(sys.argv[2].split(":")[1])
views = [y for y in range(height) if all(abs(c - g) <= 20 for c, g in zip(pixel(separator, y), (98, 100, 102)))]
counts = {}
for y in views:
    for x in range(width):
        counts[pixel(x, y)] = counts.get(pixel(x, y), 0) + 1
background = max(counts, key=counts.get)
out = [str(width), str(height), str(colour), str(len(views))]
for band in sys.argv[2:]:
    x0, x1 = (int(v) for v in band.split(":"))
    blue = red = green = black = white = 0
    for y in views:
        for x in range(x0, x1):
            r, g, b = pixel(x, y)
            blue += b > 170 and r < 60 and g < 110
            red += r > 170 and g < 90 and b < 60
            green += g > 170 and r < 90 and b < 60
            black += max(r, g, b) < 100 and max(abs(r - background[0]), abs(g - background[1]), abs(b - background[2])) > 12
            white += min(r, g, b) > 180
    out += [str(blue), str(red), str(green), str(black), str(white)]
print(" ".join(out))
EOF
}

# Distinct colours in the columns [x0, x1) of a PNG.
distinct_colours() {  # png x0 x1
  python3 - "$repo/tests/support" "$@" <<'EOF'
import sys
sys.path.insert(0, sys.argv[1])
from png_pixels import read_png
rows, n, colour = read_png(sys.argv[2], with_type=True)
x0, x1 = int(sys.argv[3]), int(sys.argv[4])
print(len({tuple(row[n * x:n * x + 3]) for row in rows for x in range(x0, x1)}))
EOF
}

# Figure 13: four columns of 300 pixels.
if "$exe" figure 13 -o "$work/fig" --supersample 1 > "$work/out.txt" 2> "$work/err.txt"; then
  [ -f "$work/fig/fig13.png" ] || fail "figure 13 wrote no fig13.png ($(cat "$work/out.txt"))"
  read -r width height type rows \
    b1 r1 g1 k1 w1 b2 r2 g2 k2 w2 b3 r3 g3 k3 w3 b4 r4 g4 k4 w4 \
    <<< "$(count_colours "$work/fig/fig13.png" 0:300 300:600 600:900 900:1200)"
  [ "$width" = 1200 ] && [ "$type" = 2 ] || fail "fig13.png is ${width} wide of colour type $type (expected 1200, RGB 2)"
  colours="$(distinct_colours "$work/fig/fig13.png" 600 900)"
  [ "$colours" -gt 2000 ] || fail "fig13.png's curvature column has $colours colours (banded)"
  [ "$rows" -ge 900 ] && [ "$rows" -le "$((height - 400))" ] || fail "fig13.png: $rows of its $height rows are views' (not five rows of views above strips)"
  # Curvature column: both signs and the green band, each over a sizeable area.
  [ "$b3" -gt 3000 ] || fail "curvature column: $b3 blue (negative K) pixels"
  [ "$r3" -gt 3000 ] || fail "curvature column: $r3 red (positive K) pixels"
  [ "$g3" -gt 3000 ] || fail "curvature column: $g3 green (K near zero) pixels"
  # Highlight column: black and white stripes, no map colours.
  [ "$k4" -gt 2000 ] && [ "$w4" -gt 2000 ] || fail "highlight column: $k4 dark, $w4 light pixels (no stripes)"
  [ $((b4 + r4 + g4)) -lt 50 ] || fail "highlight column has $b4 blue, $r4 red, $g4 green pixels"
  # Net columns: dark lines over a lit surface, the twice subdivided net denser.
  [ "$w1" -gt 5000 ] && [ "$w2" -gt 5000 ] || fail "net columns: $w1 and $w2 light pixels (no lit surface under the nets)"
  [ "$k1" -gt 500 ] && [ $((4 * k2)) -gt $((5 * k1)) ] || fail "net columns: $k1 and $k2 dark pixels (the twice subdivided net must have a quarter more)"
  [ $((b1 + r1 + g1 + b2 + r2 + g2)) -lt 50 ] || fail "net columns have map colours"
else
  fail "figure 13: $(cat "$work/err.txt")"
fi

# Figure 1: RTS's eigenvectors as nets with their eigensplines, three columns (the separator at
# x = 300), two rows: every column lit surfaces (light) and black nets (dark), no map colours.
if "$exe" figure 1 -o "$work/fig" --supersample 1 > "$work/out.txt" 2> "$work/err.txt"; then
  read -r width height type rows b1 r1 g1 k1 w1 b2 r2 g2 k2 w2 b3 r3 g3 k3 w3 \
    <<< "$(count_colours "$work/fig/fig01.png" 0:300 300:600 600:900)"
  [ "$width" = 900 ] && [ "$type" = 2 ] || fail "fig01.png is ${width} wide of colour type $type (expected 900, RGB 2)"
  [ "$rows" -ge 400 ] || fail "fig01.png: only $rows rows of views"
  for column in "$k1 $w1" "$k2 $w2" "$k3 $w3"; do
    read -r dark light <<< "$column"
    [ "$dark" -gt 2000 ] && [ "$light" -gt 2000 ] || fail "fig01.png column: $dark dark, $light light pixels (no net or surface)"
  done
  [ $((b1 + r1 + g1 + b2 + r2 + g2 + b3 + r3 + g3)) -lt 50 ] || fail "fig01.png has map colours (it is shaded)"
else
  fail "figure 1: $(cat "$work/err.txt")"
fi

# Figure 11's claim, measured on its input: spoke sign changes of dK/dr over rings 1..8 (C2PS: 96,
# C2PS-U: 12, one minimum per spoke) and the first ring's K (C2PS waves up to +3.6, C2PS-U stays <= 0).
cone="$repo/assets/cap6_cone.obj"
for scheme in c2ps c2ps-u; do
  "$exe" pole "$cone" --scheme $scheme --rings 8 --json > "$work/pole_$scheme.json" 2> "$work/err.txt" ||
    fail "pole --scheme $scheme: $(cat "$work/err.txt")"
done
python3 - "$work/pole_c2ps.json" "$work/pole_c2ps-u.json" <<'EOF' || fail "fig. 11's input does not show the uniform first step's more monotone K"
import json, sys
direct, uniform = (json.load(open(p))["poles"][0] for p in sys.argv[1:])
print("spoke sign changes: c2ps", direct["spoke_sign_changes"], "c2ps-u", uniform["spoke_sign_changes"],
      "; ring 1 K_max", direct["rings"][0]["K_max"], uniform["rings"][0]["K_max"])
assert uniform["spoke_sign_changes"] * 4 <= direct["spoke_sign_changes"]
assert uniform["rings"][0]["dK_dr_sign_changes"] == 0 < direct["rings"][0]["dK_dr_sign_changes"]
assert uniform["rings"][0]["K_max"] <= 1e-9 < 1.0 < direct["rings"][0]["K_max"]
EOF

# render: one shading per view; the JSON says which.
saddle="$repo/assets/cap12_saddle.obj"
if json="$("$exe" render "$saddle" -o "$work/two.png" --scheme c2ps,rts-u --shade gaussian,highlight --level 3 \
    --size 400x260 --no-poles --time 1 2> "$work/err.txt")"; then
  echo "$json" | grep -q '"shades":\["gaussian","highlight"\]' || fail "render JSON lacks the per-view shades: $json"
  echo "$json" | grep -q '"titles":\["C2PS · 3","RTS-U · 3"\]' || fail "rts-u did not render: $json"
  read -r width height type rows b1 r1 g1 k1 w1 b2 r2 g2 k2 w2 <<< "$(count_colours "$work/two.png" 0:200 200:400)"
  [ "$b1" -gt 400 ] || fail "gaussian view of the saddle: $b1 blue pixels"
  [ $((b2 + r2 + g2)) -lt 20 ] || fail "highlight view has map colours ($b2 blue, $r2 red, $g2 green)"
  [ "$k2" -gt 300 ] && [ "$w2" -gt 300 ] || fail "highlight view: $k2 dark, $w2 light pixels"
else
  fail "render --shade gaussian,highlight: $(cat "$work/err.txt")"
fi

# Usage errors: exit 2, no output.
expect_usage() {  # description args...
  local what="$1"
  shift
  "$exe" "$@" > /dev/null 2>&1
  local rc=$?
  [ $rc -eq 2 ] || fail "$what: exit $rc, expected 2"
}
expect_usage "three shades for two views" render "$saddle" -o "$work/x.png" --scheme c2ps,rts --shade gaussian,highlight,shaded
expect_usage "gaussian and mean in one image" render "$saddle" -o "$work/x.png" --scheme c2ps,rts --shade gaussian,mean
expect_usage "figure 3" figure 3 -o "$work/x"
expect_usage "figure without a number" figure -o "$work/x"
expect_usage "figure without -o" figure 13
[ ! -e "$work/x.png" ] && [ ! -e "$work/x" ] || fail "a usage error left output behind"

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "render_figure: all checks passed"
