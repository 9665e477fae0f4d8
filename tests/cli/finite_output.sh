#!/usr/bin/env bash
# No output ever holds inf or NaN. The reader refuses coordinates over 1e150 (a globe scaled by
# 1e307 made refine write "v -nan 0 inf" and pole print NaN normals); under the limit every command
# gives finite numbers (pole's K and H scale exactly). Args: <polarview executable> <repository root>.
set -u
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# A globe with every coordinate multiplied by $1, written to $2.
scaled_globe() {
  awk -v s="$1" '$1 == "v" { printf "v %.17g %.17g %.17g\n", $2 * s, $3 * s, $4 * s; next } { print }' \
    "$tmp/globe.obj" > "$2"
}
"$exe" shape globe --valence 12 --links 6 -o "$tmp/globe.obj" || fail "shape globe"
scaled_globe 1e307 "$tmp/huge.obj"
scaled_globe 1e140 "$tmp/large.obj"

# Over the limit: every command exits 1 with one line naming FILE:1 (the first vertex), no output.
expect_refused() {  # WHAT OUTPUT command...
  local what=$1 output=$2
  shift 2
  "$@" > "$tmp/out.txt" 2> "$tmp/err.txt"
  local rc=$?
  [ $rc -eq 1 ] || fail "$what: exit $rc, expected 1"
  [ "$(wc -l < "$tmp/err.txt")" -eq 1 ] || fail "$what: expected one stderr line: $(head -c 300 "$tmp/err.txt")"
  grep -q "^polarview: $tmp/huge.obj:1: coordinate .* is too large (the limit is 1e150)$" "$tmp/err.txt" ||
    fail "$what: message: $(cat "$tmp/err.txt")"
  if grep -qiE 'nan|inf' "$tmp/out.txt"; then fail "$what: printed a non-finite number"; fi
  [ -z "$output" ] || [ ! -e "$output" ] || fail "$what: wrote $output"
}
for scheme in cc c2ps rts bps; do
  expect_refused "refine $scheme" "$tmp/huge.$scheme.obj" "$exe" refine "$tmp/huge.obj" -o "$tmp/huge.$scheme.obj" --scheme $scheme --levels 2
done
for scheme in c2ps rts bps; do
  expect_refused "pole $scheme" "" "$exe" pole "$tmp/huge.obj" --scheme $scheme
  expect_refused "pole $scheme --json" "" "$exe" pole "$tmp/huge.obj" --scheme $scheme --json
done
expect_refused "info" "" "$exe" info "$tmp/huge.obj" --json
expect_refused "bench" "" "$exe" bench "$tmp/huge.obj" --scheme c2ps --levels 1 --reps 1 --json
# render (when built with the viewer) fails on loading, before any window.
"$exe" render "$tmp/huge.obj" -o "$tmp/huge.png" > /dev/null 2> "$tmp/err.txt"
if [ $? -ne 2 ] || ! grep -q "built without the viewer" "$tmp/err.txt"; then
  expect_refused "render" "$tmp/huge.png" "$exe" render "$tmp/huge.obj" -o "$tmp/huge.png"
fi

# Under the limit: finite results everywhere, and pole's numbers are the unit globe's, scaled.
for scheme in cc c2ps rts bps; do
  "$exe" refine "$tmp/large.obj" -o "$tmp/large.$scheme.obj" --scheme $scheme --levels 3 ||
    fail "refine $scheme of a globe scaled by 1e140"
  if grep -qiE 'nan|inf' "$tmp/large.$scheme.obj"; then fail "refine $scheme wrote a non-finite coordinate"; fi
  "$exe" info "$tmp/large.$scheme.obj" > /dev/null || fail "refine $scheme: output does not read back"
done
for scheme in c2ps rts bps; do
  "$exe" pole "$tmp/globe.obj" --scheme $scheme --json > "$tmp/unit.json" || fail "pole $scheme unit"
  "$exe" pole "$tmp/large.obj" --scheme $scheme --json > "$tmp/large.json" || fail "pole $scheme 1e140"
  "$exe" pole "$tmp/large.obj" --scheme $scheme > "$tmp/large.txt" || fail "pole $scheme 1e140 (text)"
  if grep -qiE 'nan|inf' "$tmp/large.txt"; then fail "pole $scheme printed a non-finite number: $(cat "$tmp/large.txt")"; fi
  python3 -c "
import json, math, sys
unit = json.load(open('$tmp/unit.json'))['poles']
large = json.load(open('$tmp/large.json'))['poles']
assert len(unit) == len(large) == 2, (len(unit), len(large))
s = 1e140
for u, l in zip(unit, large):
    assert all(abs(a - b) < 1e-12 for a, b in zip(u['normal'], l['normal'])), (u['normal'], l['normal'])
    if u['gaussian_curvature'] is None:
        assert l['gaussian_curvature'] is None
        continue
    assert math.isclose(l['gaussian_curvature'] * s * s, u['gaussian_curvature'], rel_tol=1e-9), (l, u)
    assert math.isclose(l['mean_curvature'] * s, u['mean_curvature'], rel_tol=1e-9), (l, u)
" || fail "pole $scheme: the 1e140 globe's normal, K, H are not the unit globe's, scaled"
done
"$exe" bench "$tmp/large.obj" --scheme c2ps --levels 2 --reps 1 --json > "$tmp/bench.json" || fail "bench 1e140"
python3 -c "import json; json.load(open('$tmp/bench.json'))" || fail "bench JSON"

echo "finite_output: $failures failures"
[ $failures -eq 0 ]
