#!/usr/bin/env bash
# --threads N and POLARVIEW_THREADS (parallel_for.h): the output is the same file byte for byte on 1,
# 2 and 3 threads (a uniform refinement large enough that its passes split, a STEP export, the
# continuity report, whose side search splits at any size); bad
# values are refused with a first line naming the setting and exit status 2.
# Args: <polarview executable> <repository root>
set -euo pipefail
exe=$1
root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
export SOURCE_DATE_EPOCH=0

"$exe" shape torus --valence 96 --links 96 -o "$tmp/torus.obj" > /dev/null
for t in 1 2 3; do
  "$exe" refine "$tmp/torus.obj" --scheme cc --levels 2 --threads "$t" -o "$tmp/refined$t.obj" > /dev/null
  mkdir "$tmp/$t"  # the same file name: a STEP file names itself
  "$exe" export "$root/assets/default.obj" --scheme c2ps --level 4 --threads "$t" -o "$tmp/$t/default.step" > /dev/null
  "$exe" continuity "$root/assets/default.obj" --scheme c2ps --level 4 --threads "$t" --json > "$tmp/continuity$t.json"
done
POLARVIEW_THREADS=2 "$exe" refine "$tmp/torus.obj" --scheme cc --levels 2 -o "$tmp/refinedenv.obj" > /dev/null
[ "$(grep -c '^f ' "$tmp/refined1.obj")" -eq $((96 * 96 * 16)) ] || fail "the torus refined to the wrong face count"
for f in refined2.obj refined3.obj refinedenv.obj; do cmp -s "$tmp/refined1.obj" "$tmp/$f" || fail "$f differs from 1 thread's"; done
for t in 2 3; do cmp -s "$tmp/1/default.step" "$tmp/$t/default.step" || fail "the STEP file on $t threads differs from 1 thread's"; done
grep -q '"seams"' "$tmp/continuity1.json" || fail "continuity printed no seams: $(head -c 300 "$tmp/continuity1.json")"
for t in 2 3; do cmp -s "$tmp/continuity1.json" "$tmp/continuity$t.json" || fail "continuity on $t threads differs from 1 thread's"; done

refused() {  # refused CODE-LINE-PATTERN COMMAND...
  local pattern=$1
  shift
  set +e
  "$@" > /dev/null 2> "$tmp/err"
  local rc=$?
  set -e
  [ $rc -eq 2 ] || fail "$*: exit $rc, expected 2"
  head -1 "$tmp/err" | grep -q "^polarview: .*$pattern" || fail "$*: $(cat "$tmp/err")"  # usage errors add the usage
}
refused "POLARVIEW_THREADS" env POLARVIEW_THREADS=many "$exe" info "$root/assets/default.obj"
refused "POLARVIEW_THREADS" env POLARVIEW_THREADS=0 "$exe" info "$root/assets/default.obj"
refused "threads" "$exe" refine "$tmp/torus.obj" --levels 1 --threads 0 -o "$tmp/x.obj"
[ ! -e "$tmp/x.obj" ] || fail "a refused --threads left a file"
echo "threads: ok"
