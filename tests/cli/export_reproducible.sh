#!/usr/bin/env bash
# CAD files name the time they were written; with SOURCE_DATE_EPOCH (reproducible-builds.org) they
# name that time instead, so one export made twice is the same bytes. A malformed value is refused
# with one line, exit 1 and no file. Usage: bash export_reproducible.sh <polarview-exe> <repo>
set -u
exe="$1"
repo="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
export_at() { SOURCE_DATE_EPOCH="$1" "$exe" export "$repo/assets/globe.obj" --scheme c2ps --level 1 -o "$2" > /dev/null; }

for ext in step igs; do
  export_at 1765000000 "$work/a.$ext" || fail "$ext export with SOURCE_DATE_EPOCH"
  sleep 1.1  # a second later: the clock alone would change the stamp
  export_at 1765000000 "$work/b.$ext" || fail "$ext export again"
  # FILE_NAME names the file: give the second the first's name to compare the rest.
  sed "s/b\.$ext/a.$ext/g" "$work/b.$ext" > "$work/b2.$ext"
  cmp -s "$work/a.$ext" "$work/b2.$ext" || fail "$ext: two exports at one SOURCE_DATE_EPOCH differ"
done
grep -q "'2025-12-06T05:46:40'" "$work/a.step" || fail "STEP stamp: $(grep FILE_NAME "$work/a.step")"
grep -q "15H20251206.054640" "$work/a.igs" || fail "IGES stamp: $(sed -n 3p "$work/a.igs")"

export_at "yesterday" "$work/bad.step" 2> "$work/err.txt"
[ $? -eq 1 ] || fail "a malformed SOURCE_DATE_EPOCH is not bad input"
grep -q "SOURCE_DATE_EPOCH: expects whole seconds" "$work/err.txt" || fail "message: $(cat "$work/err.txt")"
[ ! -e "$work/bad.step" ] || fail "a refused export left a file"

[ "$failures" -eq 0 ] || exit 1
echo "export_reproducible: ok"
