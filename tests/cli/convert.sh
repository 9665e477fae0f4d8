#!/usr/bin/env bash
# convert --ev-to-polar (paper Fig. 14): the converted corners of a refined cube are poles that
# `info` lists and C2PS refines; convert --ngon-to-fan: a Blender cylinder's 24-gon caps become
# triangle fans whose centres are two valence-24 poles; usage errors exit 2, bad input 1, and both
# leave no file.
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$exe" shape cube -o "$tmp/cube.obj"
"$exe" refine "$tmp/cube.obj" --scheme cc --levels 2 -o "$tmp/cube2.obj"
"$exe" convert "$tmp/cube2.obj" --ev-to-polar -o "$tmp/a.obj" > "$tmp/out.txt"
grep -q "8 extraordinary vertices turned into 2n-valent polar configurations" "$tmp/out.txt" || fail "$(cat "$tmp/out.txt")"
poles=$("$exe" info "$tmp/a.obj" --json | python3 -c "import json,sys; print(len(json.load(sys.stdin)['poles']))")
[ "$poles" -eq 8 ] || fail "info lists $poles poles in the converted mesh, expected 8"
"$exe" info "$tmp/a.obj" > "$tmp/info.txt"
grep -q "vertex .*: valence 6" "$tmp/info.txt" || fail "no valence-6 pole"
"$exe" convert "$tmp/cube2.obj" --ev-to-polar --pentagons -o "$tmp/c.obj" > /dev/null
"$exe" info "$tmp/c.obj" > "$tmp/info.txt"
grep -q "24 polygons" "$tmp/info.txt" || fail "pentagons: $(head -1 "$tmp/info.txt")"
"$exe" bench "$tmp/a.obj" --scheme c2ps --levels 3 --adaptive --reps 1 --json > /dev/null || fail "c2ps on the converted mesh"
set +e
"$exe" convert "$tmp/cube2.obj" -o "$tmp/none.obj" > /dev/null 2>&1
rc=$?
set -e
[ $rc -eq 2 ] || fail "convert without --ev-to-polar: exit $rc"
[ ! -e "$tmp/none.obj" ] || fail "a file was written on a usage error"

# A Blender cylinder: 24-gon caps over one ring of 24 quads. No pole; info points at the conversion.
python3 -c "
import math
n = 24
v = ['v %.17g %.17g %d' % (math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), z) for z in (-1, 1) for i in range(n)]
f = ['f %d %d %d %d' % (i + 1, (i + 1) % n + 1, n + (i + 1) % n + 1, n + i + 1) for i in range(n)]
f += ['f ' + ' '.join(str(n + i + 1) for i in range(n)), 'f ' + ' '.join(str(n - i) for i in range(n))]
open('$tmp/cylinder.obj', 'w').write('\n'.join(v + f) + '\n')"
"$exe" info "$tmp/cylinder.obj" > "$tmp/info.txt"
grep -qx "poles: 0" "$tmp/info.txt" || fail "cylinder: $(grep poles "$tmp/info.txt")"
grep -q "^  2 faces of 5 or more sides: convert --ngon-to-fan" "$tmp/info.txt" || fail "cylinder: info does not point at --ngon-to-fan"
"$exe" convert "$tmp/cylinder.obj" --ngon-to-fan -o "$tmp/fans.obj" > "$tmp/out.txt"
grep -qx "$tmp/fans.obj: 2 faces with 5 or more sides turned into triangle fans around new centre vertices (vertices 48..49)" "$tmp/out.txt" ||
  fail "ngon-to-fan: $(cat "$tmp/out.txt")"
"$exe" info "$tmp/fans.obj" --json | python3 -c "
import json, sys; d = json.load(sys.stdin)
assert (d['vertices'], d['faces'], d['triangles'], d['quads'], d['polygons']) == (50, 72, 48, 24, 0), d
p = d['poles']
assert [(x['vertex'], x['valence'], x['outer'], x.get('opposite_pole')) for x in p] == [(48, 24, 'pole', 49), (49, 24, 'pole', 48)], p
assert d['rejected_candidates'] == []" || fail "ngon-to-fan: the caps are not two valence-24 poles"
"$exe" bench "$tmp/fans.obj" --scheme c2ps --levels 3 --adaptive --reps 1 --json > /dev/null || fail "c2ps on the fans"
# One conversion a call; --pentagons is --ev-to-polar's; a malformed file: one line naming it, exit 1.
for args in "--ngon-to-fan --ev-to-polar" "--ngon-to-fan --pentagons"; do
  rc=0
  "$exe" convert "$tmp/cylinder.obj" $args -o "$tmp/both.obj" > /dev/null 2> "$tmp/err.txt" || rc=$?
  [ $rc -eq 2 ] || fail "convert $args: exit $rc"
  [ ! -e "$tmp/both.obj" ] || fail "convert $args wrote a file"
done
grep -q "^polarview: convert: --pentagons applies to --ev-to-polar" "$tmp/err.txt" || fail "$(head -1 "$tmp/err.txt")"
printf 'v 0 0 0\nv 1 0 0\nf 1 2 7\n' > "$tmp/bad.obj"
rc=0
"$exe" convert "$tmp/bad.obj" --ngon-to-fan -o "$tmp/bad_out.obj" > /dev/null 2> "$tmp/err.txt" || rc=$?
[ $rc -eq 1 ] || fail "malformed input: exit $rc"
[ "$(wc -l < "$tmp/err.txt")" -eq 1 ] && grep -q "^polarview: $tmp/bad.obj:3" "$tmp/err.txt" || fail "malformed input: $(cat "$tmp/err.txt")"
[ ! -e "$tmp/bad_out.obj" ] || fail "malformed input wrote a file"
echo ok
