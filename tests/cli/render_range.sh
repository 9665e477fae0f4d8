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
