#!/usr/bin/env bash
# `polarview render` colour range on the default mushroom (a valence-12 cap over a stem whose round
# bottom holds four valence-3 extraordinary vertices): the automatic range follows the percentile
# (P90 < P99 <= P100, the tight corners only enter at the top), a typed --range is used exactly,
# and the range is the same whichever schemes share the image. Reads "range" from --time's JSON.
# Usage: bash render_range.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1600x900x24" bash "$0" "$@"
fi
failures=0
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# The colour range of one render: render_range ARGS...
render_range() {
  "$exe" render --time 1 --shade gaussian --size 200x160 --level 3 "$@" | sed -n 's/.*"range":\([0-9.eE+-]*\).*/\1/p'
}

p90="$(render_range --percentile 90)"
p99="$(render_range --percentile 99)"
p100="$(render_range --percentile 100)"
[ -n "$p90" ] && [ -n "$p99" ] && [ -n "$p100" ] || fail "no range in the JSON ($p90 / $p99 / $p100)"
awk -v a="$p90" -v b="$p99" -v c="$p100" 'BEGIN { exit !(a > 0 && a < b && b <= c) }' ||
  fail "ranges do not grow with the percentile: P90 $p90, P99 $p99, P100 $p100"
# The tail is long: the cap's scale (P90) is well under the extreme values.
awk -v a="$p90" -v c="$p100" 'BEGIN { exit !(3 * a < c) }' || fail "P90 $p90 is not well under P100 $p100"

typed="$(render_range --range 0.375)"
[ "$typed" = "0.375" ] || fail "typed --range 0.375 came out as '$typed'"

# One shared range: the same for C2PS alone and C2PS beside C2PS (same surfaces, same weights).
one="$(render_range --scheme c2ps)"
two="$(render_range --scheme c2ps,c2ps)"
[ "$one" = "$two" ] || fail "range of one view $one differs from two equal views $two"

# A sphere (K > 0 everywhere): the automatic range is one-sided over its own values, and the image
# shows their variation in several hues (the old +-P90 painted it one red: 1 hue bucket).
globe="$2/assets/globe.obj"
json="$("$exe" render "$globe" --time 1 --shade gaussian --size 400x300 --level 3 -o "$work/globe.png")"
echo "$json" | python3 -c "
import json, sys
d = json.load(sys.stdin)
assert d['one_sided'] and 0 < d['range_min'] < d['range_max'], d" || fail "globe: range not one-sided over K > 0: $json"
# Hue buckets of 20 degrees among the saturated pixels of the views (the top 70%, above the bar).
hues="$(python3 - "$work/globe.png" "$2/tests/support" <<'PY'
import colorsys, sys
sys.path.insert(0, sys.argv[2])
from png_pixels import read_png
rows, n = read_png(sys.argv[1])
buckets = set()
for row in rows[:int(0.7 * len(rows))]:
    for i in range(0, len(row), n):
        h, s, v = colorsys.rgb_to_hsv(row[i] / 255, row[i + 1] / 255, row[i + 2] / 255)
        if s > 0.5 and v > 0.2:
            buckets.add(int(h * 18))
print(len(buckets))
PY
)"
[ "${hues:-0}" -ge 4 ] || fail "globe with the automatic range shows $hues hue buckets of 20 degrees, expected >= 4"
# Typed one-sided ranges are taken; MIN >= MAX is refused.
"$exe" render "$globe" --time 1 --shade gaussian --size 80x60 --level 1 --range 0.8:1.2 -o "$work/typed.png" |
  grep -q '"range_min":0.8,"range_max":1.2,"one_sided":true' || fail "--range 0.8:1.2 not used as typed"
"$exe" render "$globe" --range 1.2:0.8 -o "$work/bad.png" > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/bad.png" ] || fail "--range 1.2:0.8 was not refused with exit 2"

for bad in 49 101 x; do
  "$exe" render --time 1 --percentile "$bad" > /dev/null 2>&1
  rc=$?
  [ $rc -eq 2 ] || fail "--percentile $bad: exit $rc, expected 2"
done

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "render range: all checks passed"
