#!/usr/bin/env bash
# convert --ev-to-polar (paper Fig. 14): the converted corners of a refined cube are poles that
# `info` lists and C2PS refines; usage errors exit 2 and leave no file.
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
echo ok
