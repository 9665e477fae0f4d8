#!/usr/bin/env bash
# `polarview export`: a parsable BezierView file whose patch count is the PatchSet's (bench's
# "patches") with each pole cap counted as the pieces written, Group lines, the summary line; bad
# input exits 1 and usage errors exit 2, and no failure leaves an output file (or replaces one).
# Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$exe" shape mushroom --valence 12 -o "$tmp/mushroom.obj"
"$exe" shape cap --valence 5 --links 4 -o "$tmp/cap5.obj"
"$exe" shape cube -o "$tmp/cube.obj"

# Parses a .bv file (kinds 4/5 and Group lines only, every number finite); prints
# "<patches> <groups> <group names, comma-separated> <patches of kind 5 degree 3 3> <degree 5 d>" (caps: quintic in u).
parse_bv() {
  python3 - "$1" <<'EOF'
import math, sys
tokens = open(sys.argv[1]).read().split()
k = 0; patches = 0; groups = []; bicubic = 0; caps = 0
while k < len(tokens):
    t = tokens[k]
    if t == 'Group':
        int(tokens[k + 1]); groups.append(tokens[k + 2]); k += 3; continue
    assert t == '5', 'unexpected token %r at %d' % (t, k)
    du, dv = int(tokens[k + 1]), int(tokens[k + 2]); k += 3
    n = 3 * (du + 1) * (dv + 1)
    values = [float(x) for x in tokens[k:k + n]]
    assert len(values) == n and all(math.isfinite(x) for x in values), 'truncated or non-finite patch'
    k += n; patches += 1
    bicubic += (du, dv) == (3, 3); caps += du == 5
    assert groups, 'patch before any Group line'
print(patches, len(groups), ','.join(groups), bicubic, caps)
EOF
}

# Summary numbers: "OUT: N Bezier patches in G groups (regular a, boundary b, polar-ring c, pole-cap d
# for e cap sectors, end-cap f)...".
summary_field() {  # TEXT WORD -> the number before/after WORD
  python3 -c "
import re, sys
s = sys.argv[1]; w = sys.argv[2]
m = {'total': r': (\d+) Bezier patches', 'groups': r'in (\d+) groups', 'pole-cap': r'pole-cap (\d+)',
     'sectors': r'for (\d+) cap sectors', 'regular': r'regular (\d+)', 'end-cap': r'end-cap (\d+)'}[w]
print(re.search(m, s).group(1))" "$1" "$2"
}

check_export() {  # MESH SCHEME LEVEL [extra args]
  local mesh=$1 scheme=$2 level=$3
  shift 3
  local out="$tmp/$(basename "$mesh" .obj)_${scheme}_$level.bv"
  local line
  line=$("$exe" export "$mesh" --scheme "$scheme" --level "$level" -o "$out" "$@")
  [ "$(printf '%s\n' "$line" | wc -l)" -eq 1 ] || fail "export printed more than one line: $line"
  case "$line" in "$out: "*) ;; *) fail "summary does not name $out: $line" ;; esac
  read -r patches groups names bicubic caps <<< "$(parse_bv "$out")"
  [ "$patches" -eq "$(summary_field "$line" total)" ] || fail "$out: $patches patches, summary says: $line"
  [ "$groups" -eq "$(summary_field "$line" groups)" ] || fail "$out: $groups Group lines, summary says: $line"
  [ "$caps" -eq "$(summary_field "$line" pole-cap)" ] || fail "$out: $caps cap patches, summary says: $line"
  [ $((bicubic + caps)) -eq "$patches" ] || fail "$out: patches neither bicubic nor caps"
  # The PatchSet's count (bench extracts the same set), each cap sector counted as its pieces.
  local set
  set=$("$exe" bench "$mesh" --scheme "$scheme" --levels "$level" --reps 1 --json |
        python3 -c "import json,sys; print(json.load(sys.stdin)['patches'])")
  local sectors
  sectors=$(summary_field "$line" sectors)
  [ $((patches - caps + sectors)) -eq "$set" ] ||
    fail "$out: $patches written ($caps cap pieces for $sectors sectors), the PatchSet has $set"
  echo "$names"
}

names=$(check_export "$tmp/mushroom.obj" c2ps 2)
for g in regular-level-0 polar-ring-2 pole-cap-level-2 end-cap-level-2; do
  case ",$names," in *",$g,"*) ;; *) fail "mushroom: no group $g in $names" ;; esac
done
names=$(check_export "$tmp/cap5.obj" bps 1)
case ",$names," in *",pole-cap-level-1,"*) ;; *) fail "cap5 bps: no pole-cap group in $names" ;; esac
check_export "$tmp/cap5.obj" rts-u 2 > /dev/null
check_export "$tmp/cube.obj" cc 2 --uniform > /dev/null
check_export "$tmp/mushroom.obj" cc 1 > /dev/null
# A valence-5 cap needs two pieces a sector at level 0 (one at level 1 since the cap is C2 with
# the ring: its quintic fit meets 1e-7 with one piece there).
line=$("$exe" export "$tmp/cap5.obj" --scheme bps --level 0 -o "$tmp/c.bv")
[ "$(summary_field "$line" pole-cap)" -eq $((2 * $(summary_field "$line" sectors))) ] || fail "cap5: $line"

# Errors: exit code, one "polarview: " line naming the input (bad input), and no output file.
expect() {  # CODE WORDS -- args...
  local code=$1 words=$2
  shift 3
  rm -f "$tmp/out.bv"
  set +e
  "$exe" export "$@" > "$tmp/stdout.txt" 2> "$tmp/stderr.txt"
  local rc=$?
  set -e
  [ $rc -eq "$code" ] || fail "export $*: exit $rc, expected $code: $(head -c 300 "$tmp/stderr.txt")"
  [ ! -e "$tmp/out.bv" ] || fail "export $*: left $tmp/out.bv"
  grep -q "$words" "$tmp/stderr.txt" || fail "export $*: stderr lacks '$words': $(head -c 300 "$tmp/stderr.txt")"
  if [ "$code" -eq 1 ]; then
    [ "$(wc -l < "$tmp/stderr.txt")" -eq 1 ] || fail "export $*: more than one stderr line"
    head -n 1 "$tmp/stderr.txt" | grep -q "^polarview: " || fail "export $*: no 'polarview: ' prefix"
  fi
}
expect 1 "$tmp/missing.obj" -- "$tmp/missing.obj" --scheme c2ps --level 1 -o "$tmp/out.bv"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0.0.1\nf 1 2 3\n' > "$tmp/malformed.obj"
expect 1 "$tmp/malformed.obj:3: " -- "$tmp/malformed.obj" --scheme cc --level 1 -o "$tmp/out.bv"
expect 1 "memory budget" -- "$tmp/mushroom.obj" --scheme c2ps --level 12 --memory-budget 1M -o "$tmp/out.bv"
expect 2 "usage" -- "$tmp/mushroom.obj" --scheme c2ps --level x -o "$tmp/out.bv"
expect 2 "usage" -- "$tmp/mushroom.obj" --scheme c2ps --level -1 -o "$tmp/out.bv"
expect 2 "usage" -- "$tmp/mushroom.obj" --scheme c2ps --level 65 -o "$tmp/out.bv"
expect 2 "needs --level" -- "$tmp/mushroom.obj" --scheme c2ps -o "$tmp/out.bv"
expect 2 "needs -o" -- "$tmp/mushroom.obj" --scheme c2ps --level 1
expect 2 "needs --scheme" -- "$tmp/mushroom.obj" --level 1 -o "$tmp/out.bv"
expect 2 "unknown scheme" -- "$tmp/mushroom.obj" --scheme loop --level 1 -o "$tmp/out.bv"
expect 2 "unknown option" -- "$tmp/mushroom.obj" --scheme c2ps --level 1 --json -o "$tmp/out.bv"
expect 2 "applies to c2ps and rts" -- "$tmp/mushroom.obj" --scheme bps --uniform-first-step --level 1 -o "$tmp/out.bv"
expect 1 "$tmp/nodir/out.bv" -- "$tmp/mushroom.obj" --scheme c2ps --level 1 -o "$tmp/nodir/out.bv"

# A failed export leaves an existing output as it was; no temporary is left anywhere.
printf 'previous\n' > "$tmp/keep.bv"
set +e
"$exe" export "$tmp/mushroom.obj" --scheme c2ps --level 12 --memory-budget 1M -o "$tmp/keep.bv" 2> /dev/null
rc=$?
set -e
[ $rc -eq 1 ] || fail "over-budget export into an existing file: exit $rc"
[ "$(cat "$tmp/keep.bv")" = previous ] || fail "a failed export replaced the existing output"
if ls "$tmp" | grep -q '\.tmp$'; then fail "a temporary was left behind: $(ls "$tmp")"; fi

# `help` lists the command.
"$exe" help > "$tmp/help.txt"  # (grep -q would stop reading: pipefail)
grep -q "polarview export IN.obj" "$tmp/help.txt" || fail "usage text lacks export"
# The caps' measured deviation is scale-free: the mushroom and its copy of size 1e-150 report
# the same (squaring a 1e-163 deviation underflowed to "caps within 0").
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2*1e-150, $3*1e-150, $4*1e-150; next} {print}' \
  "$tmp/mushroom.obj" > "$tmp/small.obj"
"$exe" export "$tmp/mushroom.obj" -o "$tmp/unit.bv" --scheme c2ps --level 2 > "$tmp/unit.txt"
"$exe" export "$tmp/small.obj" -o "$tmp/small.bv" --scheme c2ps --level 2 > "$tmp/small.txt"
caps() { sed -n 's/.*caps within \([^ ]*\) of.*/\1/p' "$1"; }
[ -n "$(caps "$tmp/unit.txt")" ] && [ "$(caps "$tmp/unit.txt")" = "$(caps "$tmp/small.txt")" ] ||
  fail "cap deviation at 1e-150: $(caps "$tmp/small.txt"), at size 1: $(caps "$tmp/unit.txt")"
echo "export: all checks passed"
