#!/usr/bin/env bash
# OpenSubdiv's `t` crease and corner tags end to end: `refine --scheme cc` applies them (the output
# differs from the untagged mesh's), says where they are not applied, and writes the refined
# mesh's own tags (sharpness 1 less), so refining that output again continues the same surface.
# Args: <polarview executable> <repository root>.
set -u
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

cube='v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n'
cube+='f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n'
printf "$cube" > "$tmp/smooth.obj"
printf "${cube}t crease 2/1/0 0 1 2.5\nt corner 1/1/0 6 1.5\n" > "$tmp/tagged.obj"

"$exe" refine "$tmp/tagged.obj" -o "$tmp/one.obj" --scheme cc --levels 1 2> "$tmp/err.txt" || fail "refine of the tagged cube"
grep -q "1 crease edges and 1 corners ('t' tags): Catmull-Clark's rules apply them in every scheme" "$tmp/err.txt" ||
  fail "no warning on where the tags apply: $(cat "$tmp/err.txt")"
"$exe" refine "$tmp/smooth.obj" -o "$tmp/smooth1.obj" --scheme cc --levels 1 || fail "refine of the smooth cube"
cmp -s <(grep '^v ' "$tmp/one.obj") <(grep '^v ' "$tmp/smooth1.obj") && fail "the tags changed nothing"

# Level 1's tags: both halves of the crease at 1.5, the corner's vertex point at 0.5.
[ "$(grep -c '^t crease 2/1/0 [0-9]* [0-9]* 1.5$' "$tmp/one.obj")" = 2 ] || fail "level-1 crease tags: $(grep '^t ' "$tmp/one.obj")"
[ "$(grep -c '^t corner 1/1/0 [0-9]* 0.5$' "$tmp/one.obj")" = 1 ] || fail "level-1 corner tag: $(grep '^t ' "$tmp/one.obj")"

# Refining level 1 once more equals refining the input twice (to round-off).
"$exe" refine "$tmp/one.obj" -o "$tmp/two_by_one.obj" --scheme cc --levels 1 2> /dev/null || fail "refine of level 1"
"$exe" refine "$tmp/tagged.obj" -o "$tmp/two.obj" --scheme cc --levels 2 2> /dev/null || fail "refine by 2 levels"
difference=$(paste <(grep '^v ' "$tmp/two_by_one.obj") <(grep '^v ' "$tmp/two.obj") |
  awk '{ for (k = 2; k <= 4; ++k) { d = $k - $(k + 4); if (d < 0) d = -d; if (d > m) m = d } n++ } END { print (n == 98 ? m + 0 : "count " n) }')
awk -v d="$difference" 'BEGIN { exit !(d != "" && d + 0 <= 1e-12 && d !~ /count/) }' ||
  fail "level 1 refined again differs from level 2: $difference"

# Holes: `info` counts them, `refine` keeps them as `t hole` on their children (4 per hole face).
printf "${cube}t hole 1/0/0 2\n" > "$tmp/holed.obj"
"$exe" info "$tmp/holed.obj" 2> /dev/null | grep -q '^holes: 1 faces' || fail "info does not count the hole: $("$exe" info "$tmp/holed.obj" 2>&1)"
"$exe" refine "$tmp/holed.obj" -o "$tmp/holed1.obj" --scheme cc --levels 1 2> /dev/null || fail "refine of the holed cube"
[ "$(grep -c '^t hole 1/0/0 ' "$tmp/holed1.obj")" = 4 ] || fail "level-1 hole tags: $(grep '^t ' "$tmp/holed1.obj")"

echo "creases: $failures failures"
[ $failures -eq 0 ]
