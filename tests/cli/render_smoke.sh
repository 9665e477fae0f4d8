#!/usr/bin/env bash
# `polarview render` end to end: a generated globe renders to a PNG of the requested size (checked in
# the PNG header), several schemes side by side and supersampling keep that size, and bad input
# (malformed OBJ, missing file, bad options) fails with one line on stderr and writes no file.
# Usage: bash render_smoke.sh <polarview-exe> <repo>. Needs an X display: re-runs itself under Xvfb.
set -u
exe="$1"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

# A globe: poles of valence n at z = +-1 and `links` latitude rings, counter-clockwise from outside.
write_globe() {  # n links file
  awk -v n="$1" -v links="$2" 'BEGIN {
    pi = 3.14159265358979
    print "v 0 0 1"
    for (k = 1; k <= links; ++k) {
      theta = pi * k / (links + 1)
      for (j = 0; j < n; ++j) printf "v %.9f %.9f %.9f\n", sin(theta) * cos(2 * pi * j / n), sin(theta) * sin(2 * pi * j / n), cos(theta)
    }
    print "v 0 0 -1"
    bottom = 2 + links * n
    for (j = 0; j < n; ++j) printf "f 1 %d %d\n", 2 + j, 2 + (j + 1) % n
    for (k = 1; k < links; ++k)
      for (j = 0; j < n; ++j) {
        a = 2 + (k - 1) * n + j; b = 2 + (k - 1) * n + (j + 1) % n
        printf "f %d %d %d %d\n", a, a + n, b + n, b
      }
    for (j = 0; j < n; ++j) printf "f %d %d %d\n", bottom, 2 + (links - 1) * n + (j + 1) % n, 2 + (links - 1) * n + j
  }' > "$3"
}

# Width and height from the IHDR chunk (bytes 16..23, big-endian), after checking the signature.
png_size() {
  local sig
  sig="$(od -An -tx1 -N8 "$1" | tr -d ' \n')"
  [ "$sig" = "89504e470d0a1a0a" ] || { echo "not-a-png"; return; }
  od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%dx%d\n", $1*16777216 + $2*65536 + $3*256 + $4, $5*16777216 + $6*65536 + $7*256 + $8 }'
}

write_globe 8 5 "$work/globe.obj"

# 1. One view, Gaussian curvature, exact size.
"$exe" render "$work/globe.obj" -o "$work/one.png" --scheme c2ps --level 2 --shade gaussian --size 320x200 > "$work/out.txt" 2> "$work/err.txt"
rc=$?
[ $rc -eq 0 ] || fail "render exited $rc: $(cat "$work/err.txt")"
[ "$(png_size "$work/one.png")" = "320x200" ] || fail "one.png is $(png_size "$work/one.png"), expected 320x200"

# 2. Four schemes side by side, 2x supersampled, mean curvature with a typed range and a camera.
"$exe" render "$work/globe.obj" -o "$work/four.png" --scheme c2ps,rts,bps,cc --level 1 --shade mean --size 480x160 \
  --supersample 2 --range 2 --camera '{"yaw":10,"pitch":30}' > /dev/null 2> "$work/err.txt"
rc=$?
[ $rc -eq 0 ] || fail "four-view render exited $rc: $(cat "$work/err.txt")"
[ "$(png_size "$work/four.png")" = "480x160" ] || fail "four.png is $(png_size "$work/four.png"), expected 480x160"

# 3. Highlight lines, transparent background, odd size.
"$exe" render "$work/globe.obj" -o "$work/hl.png" --shade highlight --transparent --size 257x131 > /dev/null 2> "$work/err.txt"
[ $? -eq 0 ] || fail "highlight render failed: $(cat "$work/err.txt")"
[ "$(png_size "$work/hl.png")" = "257x131" ] || fail "hl.png is $(png_size "$work/hl.png"), expected 257x131"

# 4. A malformed OBJ (face index out of range on line 4): exit 1, one line naming FILE:LINE, no PNG.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n' > "$work/bad.obj"
"$exe" render "$work/bad.obj" -o "$work/bad.png" --size 320x200 > /dev/null 2> "$work/err.txt"
rc=$?
[ $rc -eq 1 ] || fail "bad.obj: exit $rc, expected 1"
[ ! -e "$work/bad.png" ] || fail "bad.obj: bad.png was written"
[ "$(wc -l < "$work/err.txt")" -eq 1 ] || fail "bad.obj: expected one line on stderr, got: $(cat "$work/err.txt")"
grep -q "^polarview: .*bad.obj:4: " "$work/err.txt" || fail "bad.obj: message lacks 'polarview: FILE:4:': $(cat "$work/err.txt")"

# 5. A missing file: exit 1, no PNG.
"$exe" render "$work/missing.obj" -o "$work/missing.png" 2> "$work/err.txt"
rc=$?
[ $rc -eq 1 ] || fail "missing.obj: exit $rc, expected 1"
[ ! -e "$work/missing.png" ] || fail "missing.obj: a PNG was written"

# 6. Usage errors: exit 2, no PNG.
for args in "--size 10" "--scheme xyz" "--level 99" "--camera {bad" "--frobnicate" "--supersample 3"; do
  # shellcheck disable=SC2086
  "$exe" render "$work/globe.obj" -o "$work/usage.png" $args > /dev/null 2>&1
  rc=$?
  [ $rc -eq 2 ] || fail "'$args': exit $rc, expected 2"
  [ ! -e "$work/usage.png" ] || fail "'$args': a PNG was written"
done

# 7. An image this GL cannot hold: a usage error (exit 2) that says what fits, one line, no PNG.
"$exe" render "$work/globe.obj" -o "$work/huge.png" --size 8192x8192 --supersample 4 > /dev/null 2> "$work/err.txt"
rc=$?
[ $rc -eq 2 ] || fail "8192x8192 at 4x: exit $rc, expected 2"
[ ! -e "$work/huge.png" ] || fail "8192x8192 at 4x: a PNG was written"
[ "$(wc -l < "$work/err.txt")" -eq 1 ] || fail "8192x8192 at 4x: expected one line, got: $(cat "$work/err.txt")"
grep -q "fits" "$work/err.txt" || fail "8192x8192 at 4x: the message does not say what fits: $(cat "$work/err.txt")"

# 8. A level deeper than the face budget allows: exit 1, one line naming the file and the deepest level.
"$exe" render "$work/globe.obj" -o "$work/deep.png" --level 20 > /dev/null 2> "$work/err.txt"
rc=$?
[ $rc -eq 1 ] || fail "level 20: exit $rc, expected 1"
[ ! -e "$work/deep.png" ] || fail "level 20: a PNG was written"
grep -q "^polarview: .*globe.obj: level 20 refused: C2PS stops at level [0-9]" "$work/err.txt" ||
  fail "level 20: unexpected message: $(cat "$work/err.txt")"

# 9. RTS with the uniform first step (the paper's Fig. 11) is a scheme of its own; RTS at a
#    valence-4 pole says in the view title that Catmull-Clark refined it.
"$exe" render "$work/globe.obj" --scheme rts,rts-u --level 2 --time 1 > "$work/out.txt" 2> "$work/err.txt" ||
  fail "rts,rts-u: $(cat "$work/err.txt")"
grep -q '"titles":\["RTS · 2","RTS-U · 2"\]' "$work/out.txt" || fail "rts,rts-u titles: $(cat "$work/out.txt")"
write_globe 4 5 "$work/globe4.obj"
"$exe" render "$work/globe4.obj" --scheme rts,c2ps --level 2 --time 1 > "$work/out.txt" 2> "$work/err.txt" ||
  fail "valence 4: $(cat "$work/err.txt")"
grep -q '"poles_by_cc":\[2,0\]' "$work/out.txt" || fail "valence 4: RTS poles not reported as CC: $(cat "$work/out.txt")"
grep -q '"RTS · 2 · poles by CC (valence < 5)"' "$work/out.txt" || fail "valence 4 title: $(cat "$work/out.txt")"

# 10. An asymmetric range MIN:MAX (two slopes, zero in the middle); MIN must be below MAX (one sign:
# one-sided, tests/cli/render_range.sh).
"$exe" render "$work/globe.obj" --range -1:3 --level 1 --time 1 > "$work/out.txt" 2> "$work/err.txt" ||
  fail "--range -1:3: $(cat "$work/err.txt")"
grep -q '"range_min":-1,"range_max":3' "$work/out.txt" || fail "--range -1:3: $(cat "$work/out.txt")"
"$exe" render "$work/globe.obj" -o "$work/r.png" --range 3:1 > /dev/null 2>&1
[ $? -eq 2 ] || fail "--range 3:1 is not a usage error"

# The reader's warnings reach stderr as with the other commands (an unreferenced vertex), and the
# image is still written.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n' > "$work/unref.obj"
"$exe" render "$work/unref.obj" -o "$work/unref.png" --scheme cc --level 1 --size 64x48 2> "$work/unref.err" >/dev/null ||
  fail "render with an unreferenced vertex failed"
grep -q "^polarview: warning: .*unref.obj: 1 unreferenced vertices ignored" "$work/unref.err" || fail "render did not print the load warning"
[ -s "$work/unref.png" ] || fail "render with a warning wrote no image"

# Pole markers over the control net: the net's lines meet in front of the pole and used to hide its
# ring (P did nothing while the net was shown).
"$exe" render -o "$work/net.png" --net --size 300x200 >/dev/null 2>&1 &&
  "$exe" render -o "$work/net_nopoles.png" --net --no-poles --size 300x200 >/dev/null 2>&1 ||
  fail "render --net failed"
cmp -s "$work/net.png" "$work/net_nopoles.png" && fail "render --net: the pole marker is hidden by the net"

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "render smoke: all checks passed"
