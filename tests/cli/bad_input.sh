#!/usr/bin/env bash
# Bad OBJ input end to end: for each broken file, `polarview info` and `polarview refine` exit 1
# (no crash), print exactly one stderr line "polarview: FILE:LINE: msg" naming the file (and the
# offending line where there is one), and `refine` leaves no output file behind.
# Usage: bash bad_input.sh <polarview-exe> <repo>
set -u
exe="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
checks=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Runs one command on a bad file and checks the error contract.
#   expect_error NAME LINE WORDS -- command args...
# LINE is the expected OBJ line ("" when the error has no line); WORDS must appear in the message.
expect_error() {
  local name="$1" line="$2" words="$3"
  shift 4
  local file="$work/$name.obj"
  "$@" > "$work/out.txt" 2> "$work/err.txt"
  local rc=$?
  checks=$((checks + 1))
  local what="$name ($2)"
  [ $rc -lt 128 ] || fail "$what: crashed with exit $rc"
  [ $rc -eq 1 ] || fail "$what: exit $rc, expected 1; stderr: $(head -c 300 "$work/err.txt")"
  local lines
  lines="$(wc -l < "$work/err.txt")"
  [ "$lines" -eq 1 ] || fail "$what: expected one stderr line, got $lines: $(head -c 300 "$work/err.txt")"
  local msg
  msg="$(head -n 1 "$work/err.txt")"
  case "$msg" in
    "polarview: "*) ;;
    *) fail "$what: stderr does not start with 'polarview: ': $msg" ;;
  esac
  case "$msg" in
    *"$file"*) ;;
    *) fail "$what: message does not name $file: $msg" ;;
  esac
  if [ -n "$line" ]; then
    case "$msg" in
      *"$file:$line: "*) ;;
      *) fail "$what: message does not point at line $line: $msg" ;;
    esac
  fi
  case "$msg" in
    *"$words"*) ;;
    *) fail "$what: message lacks '$words': $msg" ;;
  esac
}

# Checks `info` and `refine` on $work/NAME.obj (already written).
check_file() {  # NAME LINE WORDS
  local name="$1" file="$work/$1.obj" out="$work/$1.out.obj"
  expect_error "$1" "$2" "$3" -- "$exe" info "$file"
  expect_error "$1" "$2" "$3" -- "$exe" refine "$file" -o "$out" --scheme cc --levels 1
  [ ! -e "$out" ] || fail "$name: refine wrote $out"
  [ ! -e "$out.tmp" ] || fail "$name: refine left $out.tmp"
}

tri='v 0 0 0\nv 1 0 0\nv 0 1 0\n'

# Empty file, and one holding only blank lines and a comment.
: > "$work/empty.obj"
check_file empty "" "empty file"
printf '\n  \n# nothing\n' > "$work/blank.obj"
check_file blank "" "no vertices or faces"

# Binary garbage: an ELF-like header with NUL bytes on line 2, then random bytes.
{ printf 'v 0 0 0\n\177ELF\002\001\001\000\000\000'; head -c 4096 /dev/urandom; } > "$work/binary.obj"
check_file binary 2 "binary"
head -c 8192 /dev/urandom > "$work/random.obj"
check_file random "" ""

# Non-finite and malformed coordinates.
printf 'v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n' > "$work/nan.obj"
check_file nan 2 "NaN"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n' > "$work/inf.obj"
check_file inf 3 "infinite"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0.0.1\nf 1 2 3\n' > "$work/malformed.obj"
check_file malformed 3 "malformed number"
printf 'v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n' > "$work/shortvertex.obj"
check_file shortvertex 2 "coordinates"
# Coordinates whose squares overflow: over the reader's limit of 1e150.
printf 'v 0 0 0\nv 1e151 0 0\nv 0 1 0\nf 1 2 3\n' > "$work/toolarge.obj"
check_file toolarge 2 "is too large (the limit is 1e150)"

# Bad face indices.
printf "${tri}f 1 2 9\n" > "$work/range.obj"
check_file range 4 "face index 9 out of range (3 vertices)"
printf "${tri}f -1 -2 -7\n" > "$work/negrange.obj"
check_file negrange 4 "face index -7 out of range"
printf "${tri}f 1 0 2\n" > "$work/zero.obj"
check_file zero 4 "face index 0"
printf "${tri}f 1 2 99999999999999999999\n" > "$work/huge.obj"
check_file huge 4 "too large"
# 64-bit extremes: negating LLONG_MIN was undefined and let this face through (exit 0, output
# written) when a vertex followed it.
printf "${tri}f 1 2 -9223372036854775808\nv 1 1 1\n" > "$work/llmin.obj"
check_file llmin 4 "face index -9223372036854775808 out of range (3 vertices)"
printf "${tri}f 1 2 -99999999999999999999999\n" > "$work/hugeneg.obj"
check_file hugeneg 4 "out of range (3 vertices)"
printf "${tri}f 1 2 9223372036854775807\n" > "$work/llmax.obj"
check_file llmax 4 "is too large"
printf "${tri}f 1 2\n" > "$work/twovertex.obj"
check_file twovertex 4 "face has 2 vertices"

# Not bad input: what OpenSubdiv refines, polarview refines as it does (manifold_split.h): a face
# repeating a vertex, three faces on an edge, two cones touching at a vertex, a face twice, faces
# turned against each other. `info` names the non-manifold parts, `refine` writes the surface.
accepts() {  # NAME
  local file="$work/$1.obj" out="$work/$1.out.obj"
  "$exe" info "$file" > "$work/$1.info" 2>/dev/null || fail "$1: info refused a mesh OpenSubdiv refines"
  grep -q "^non-manifold: " "$work/$1.info" || fail "$1: info does not name the non-manifold parts"
  "$exe" refine "$file" -o "$out" --scheme cc --levels 2 2>/dev/null || fail "$1: refine refused a mesh OpenSubdiv refines"
  grep -q '^f ' "$out" || fail "$1: refine wrote no faces"
  ! grep -qi 'nan\|inf' "$out" || fail "$1: refine wrote a non-finite number"
}
printf "${tri}f 1 2 3 2\n" > "$work/repeat.obj"
accepts repeat
printf "${tri}v 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 2 1 5\n" > "$work/edge3.obj"
accepts edge3
printf 'v 0 0 0\nv 1 0 1\nv 0 1 1\nv -1 -1 1\nv 1 0 -1\nv 0 1 -1\nv -1 -1 -1\n' > "$work/cones.obj"
printf 'f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\nf 1 6 5\nf 1 7 6\nf 1 5 7\nf 5 6 7\n' >> "$work/cones.obj"
accepts cones
printf "${tri}v 1 1 0\nf 1 2 3\nf 2 4 3\nf 3 1 2\n" > "$work/duplicate.obj"
accepts duplicate
printf "${tri}v 1 1 0\nf 1 2 3\nf 2 3 4\n" > "$work/orientation.obj"
accepts orientation

# Bad `t` tags (OpenSubdiv's crease/corner/hole syntax, 0-based ids): counts, values, ids.
printf "${tri}f 1 2 3\nt crease 2/1/0 0 1\n" > "$work/tagcount.obj"
check_file tagcount 5 "tag 'crease' has 2 values, its counts 2/1/0 say 3"
printf "${tri}f 1 2 3\nt crease 2/1/0 0 1 -2\n" > "$work/tagsharp.obj"
check_file tagsharp 5 "sharpness -2 is negative"
printf "t corner 1/1/0 3 1\n${tri}f 1 2 3\n" > "$work/tagrange.obj"
check_file tagrange 1 "vertex id 3 out of range (3 vertices; tag ids are 0-based)"

# A file of NUL bytes is refused at its first chunk, naming line 1 (it used to be read whole first).
head -c 33554432 /dev/zero > "$work/zeros.obj"
check_file zeros 1 "binary data (NUL byte)"

# A missing file fails the same way (no line).
expect_error missing "" "" -- "$exe" info "$work/missing.obj"

echo "bad_input: $checks commands checked, $failures failures"
[ $failures -eq 0 ]
