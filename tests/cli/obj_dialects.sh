#!/usr/bin/env bash
# OBJ files as other programs write them: a UTF-8 byte-order mark (was "unknown statement"), CR-only
# line ends of old Mac files (was "malformed number") and CRLF read as the LF file does, with the
# same line numbers in errors. And pole's note on missing curvature names the right cause: BPS (C1
# at the pole) only under --scheme bps, a degenerate tangent plane under any scheme.
# Args: <polarview executable> <repository root>.
set -u
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$exe" shape globe --valence 8 --links 4 -o "$tmp/lf.obj" || fail "shape globe"
"$exe" refine "$tmp/lf.obj" -o "$tmp/lf.out.obj" --scheme c2ps --levels 1 || fail "refine of the LF file"
{ printf '\357\273\277'; cat "$tmp/lf.obj"; } > "$tmp/bom.obj"
tr '\n' '\r' < "$tmp/lf.obj" > "$tmp/cr.obj"
sed 's/$/\r/' "$tmp/lf.obj" > "$tmp/crlf.obj"
{ printf '\357\273\277'; tr '\n' '\r' < "$tmp/lf.obj"; } > "$tmp/bomcr.obj"
for name in bom cr crlf bomcr; do
  file="$tmp/$name.obj"
  "$exe" info "$file" > "$tmp/$name.info" 2> "$tmp/err.txt" || fail "$name: info failed: $(cat "$tmp/err.txt")"
  [ ! -s "$tmp/err.txt" ] || fail "$name: info printed on stderr: $(cat "$tmp/err.txt")"
  # The same mesh: the same counts after the file name, the same refined output.
  diff <(cut -d: -f2- "$tmp/$name.info") <("$exe" info "$tmp/lf.obj" | cut -d: -f2-) > /dev/null ||
    fail "$name: info differs from the LF file's"
  "$exe" refine "$file" -o "$tmp/$name.out.obj" --scheme c2ps --levels 1 || fail "$name: refine failed"
  cmp -s "$tmp/$name.out.obj" "$tmp/lf.out.obj" || fail "$name: refine output differs from the LF file's"
done

# Errors in CR-only and CRLF files name the line as in the LF file.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0.0.1\nf 1 2 3\n' > "$tmp/badlf.obj"
tr '\n' '\r' < "$tmp/badlf.obj" > "$tmp/badcr.obj"
sed 's/$/\r/' "$tmp/badlf.obj" > "$tmp/badcrlf.obj"
{ printf '\357\273\277'; cat "$tmp/badcr.obj"; } > "$tmp/badbomcr.obj"
for name in badlf badcr badcrlf badbomcr; do
  "$exe" info "$tmp/$name.obj" > /dev/null 2> "$tmp/err.txt"
  rc=$?
  [ $rc -eq 1 ] || fail "$name: exit $rc, expected 1"
  [ "$(cat "$tmp/err.txt")" = "polarview: $tmp/$name.obj:3: malformed number '0.0.1'" ] ||
    fail "$name: message: $(cat "$tmp/err.txt")"
done
# A byte-order mark anywhere but the start is still an error.
{ printf 'v 0 0 0\n\357\273\277'; tail -n +2 "$tmp/lf.obj"; } > "$tmp/midbom.obj"
"$exe" info "$tmp/midbom.obj" > /dev/null 2> "$tmp/err.txt"
grep -q "midbom.obj:2: unknown statement" "$tmp/err.txt" || fail "midbom: $(cat "$tmp/err.txt")"

# pole: the BPS note under bps only; a degenerate tangent plane (every vertex at the origin, so
# p1 = p2 = 0) says so under every scheme.
"$exe" pole "$tmp/lf.obj" --scheme bps > "$tmp/pole.txt" || fail "pole bps"
[ "$(grep -c '(curvature not defined: BPS is C1 at the pole)$' "$tmp/pole.txt")" -eq 2 ] ||
  fail "pole bps: the BPS note is missing: $(cat "$tmp/pole.txt")"
for scheme in c2ps c2ps-u rts rts-u; do
  "$exe" pole "$tmp/lf.obj" --scheme $scheme > "$tmp/pole.txt" || fail "pole $scheme"
  if grep -q 'not defined' "$tmp/pole.txt"; then fail "pole $scheme: a note on a regular globe: $(cat "$tmp/pole.txt")"; fi
done
awk '$1 == "v" { print "v 0 0 0"; next } { print }' "$tmp/lf.obj" > "$tmp/point.obj"
for scheme in c2ps rts bps; do
  "$exe" pole "$tmp/point.obj" --scheme $scheme > "$tmp/pole.txt" || fail "pole $scheme on a degenerate globe"
  if grep -q 'BPS' "$tmp/pole.txt"; then fail "pole $scheme: the note blames BPS: $(cat "$tmp/pole.txt")"; fi
  [ "$(grep -c '(no tangent plane: p1 x p2 = 0, normal and curvature not defined)$' "$tmp/pole.txt")" -eq 2 ] ||
    fail "pole $scheme: no degenerate-tangent-plane note: $(cat "$tmp/pole.txt")"
done

echo "obj_dialects: $failures failures"
[ $failures -eq 0 ]
