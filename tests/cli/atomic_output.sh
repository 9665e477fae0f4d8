#!/usr/bin/env bash
# Outputs are written atomically through a temporary of their own: two processes refining to one
# output in parallel each leave a whole file (with a shared OUT.tmp they interleaved), a user's
# OUT.tmp and a symlink named OUT.tmp are never touched (they were clobbered / followed), and
# SIGTERM during a long write leaves no temporary (OUT.tmp stayed). Each case runs with the
# O_TMPFILE path and with named temporaries (POLARVIEW_NAMED_TEMPORARIES=1, as on a file system
# without O_TMPFILE). Args: <polarview executable> <repository root>.
set -u
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
listing() { (cd "$1" && ls -A | sort | tr '\n' ' '); }

faces_of() { "$exe" info "$1" --json | python3 -c "import json, sys; print(json.load(sys.stdin)['faces'])"; }
# Two tori of about the same size (so the two writers overlap) and different face counts.
"$exe" shape torus --valence 96 --links 64 -o "$tmp/torus.obj" || fail "shape torus"
"$exe" shape torus --valence 100 --links 64 -o "$tmp/torus2.obj" || fail "shape torus"
faces1=$(( $(faces_of "$tmp/torus.obj") * 64 ))
faces2=$(( $(faces_of "$tmp/torus2.obj") * 64 ))

for named in 0 1; do
  export POLARVIEW_NAMED_TEMPORARIES=$named
  dir="$tmp/out$named"
  mkdir -p "$dir"

  # Two writers, one output: either whole result is recognisable by its face count.
  for round in 1 2 3; do
    "$exe" refine "$tmp/torus.obj" -o "$dir/same.obj" --scheme cc --levels 3 2> "$tmp/err1.txt" &
    first=$!
    "$exe" refine "$tmp/torus2.obj" -o "$dir/same.obj" --scheme cc --levels 3 2> "$tmp/err2.txt" &
    second=$!
    wait $first || fail "named=$named round $round: first writer failed: $(cat "$tmp/err1.txt")"
    wait $second || fail "named=$named round $round: second writer failed: $(cat "$tmp/err2.txt")"
    faces=$(faces_of "$dir/same.obj" 2> "$tmp/err.txt")
    case "$faces" in
      "$faces1" | "$faces2") ;;
      *) fail "named=$named round $round: the output is not one whole result (faces '$faces'): $(head -c 200 "$tmp/err.txt")" ;;
    esac
    [ "$(listing "$dir")" = "same.obj " ] || fail "named=$named round $round: left behind: $(listing "$dir")"
  done

  # A user's OUT.tmp, a symlink named OUT.tmp (to a file, and dangling): untouched.
  printf 'mine\n' > "$dir/a.obj.tmp"
  printf 'keep me\n' > "$dir/victim.txt"
  ln -s victim.txt "$dir/b.obj.tmp"
  ln -s nowhere.txt "$dir/c.obj.tmp"
  for name in a b c; do
    "$exe" refine "$tmp/torus.obj" -o "$dir/$name.obj" --scheme c2ps --levels 1 || fail "named=$named: refine to $name.obj"
    [ "$(faces_of "$dir/$name.obj")" -eq $((faces1 / 16)) ] || fail "named=$named: $name.obj is not the refined torus"
  done
  [ "$(cat "$dir/a.obj.tmp")" = "mine" ] || fail "named=$named: the user's a.obj.tmp was changed"
  [ "$(readlink "$dir/b.obj.tmp")" = "victim.txt" ] || fail "named=$named: the symlink b.obj.tmp was replaced"
  [ "$(cat "$dir/victim.txt")" = "keep me" ] || fail "named=$named: written through the symlink b.obj.tmp"
  [ "$(readlink "$dir/c.obj.tmp")" = "nowhere.txt" ] || fail "named=$named: the symlink c.obj.tmp was replaced"
  [ ! -e "$dir/nowhere.txt" ] || fail "named=$named: the dangling symlink c.obj.tmp was followed"
  [ "$(listing "$dir")" = "a.obj a.obj.tmp b.obj b.obj.tmp c.obj c.obj.tmp same.obj victim.txt " ] ||
    fail "named=$named: unexpected files: $(listing "$dir")"

  # SIGTERM while a big shape is being written (once the process has a file open in the
  # directory): no output, no temporary, and the process dies of the signal. SIGKILL cannot be
  # caught: only the unnamed O_TMPFILE temporary leaves nothing then.
  kill_dir="$dir/kill"
  mkdir -p "$kill_dir"
  printf 'old\n' > "$kill_dir/keep.obj"
  signals=TERM
  [ "$named" = 1 ] || signals="TERM KILL"
  for signal in $signals; do
    "$exe" shape torus --valence 1200 --links 800 -o "$kill_dir/big.obj" &
    pid=$!
    for _ in $(seq 1 2000); do
      ls -l /proc/$pid/fd 2> /dev/null | grep -q -- "$kill_dir/" && break
      kill -0 $pid 2> /dev/null || break
      sleep 0.005
    done
    kill -$signal $pid 2> /dev/null
    { wait $pid; } 2> /dev/null
    rc=$?
    [ $rc -eq $((128 + $(kill -l $signal))) ] || fail "named=$named: the writer was not killed by SIG$signal during the write (exit $rc)"
    [ "$(listing "$kill_dir")" = "keep.obj " ] || fail "named=$named: SIG$signal left: $(listing "$kill_dir")"
    [ "$(cat "$kill_dir/keep.obj")" = "old" ] || fail "named=$named: SIG$signal changed another file"
  done
done

# Outputs that are not regular files are written into, never replaced: a FIFO (with a reader),
# /dev/stdout to a pipe and to the shell's file (a symlink into /proc: as root, replacing it broke
# the machine's /dev/stdout), /dev/null. A read-only output is refused and kept, even for root.
nodes="$tmp/nodes"
mkdir -p "$nodes"
mkfifo "$nodes/fifo"
cat "$nodes/fifo" > "$nodes/from_fifo.obj" &
reader=$!
"$exe" refine "$tmp/torus.obj" -o "$nodes/fifo" --scheme cc --levels 1 || fail "refine into a FIFO"
wait $reader
[ -p "$nodes/fifo" ] || fail "the FIFO was replaced"
[ "$(faces_of "$nodes/from_fifo.obj")" -eq $((faces1 / 16)) ] || fail "the FIFO's reader did not get the refined torus"
piped=$("$exe" refine "$tmp/torus.obj" -o /dev/stdout --scheme cc --levels 1 | grep -c '^f ')
[ "$piped" -eq $((faces1 / 16)) ] || fail "-o /dev/stdout into a pipe gave $piped faces"
"$exe" refine "$tmp/torus.obj" -o /dev/stdout --scheme cc --levels 1 > "$nodes/redirected.obj" || fail "-o /dev/stdout into a file"
[ "$(faces_of "$nodes/redirected.obj")" -eq $((faces1 / 16)) ] || fail "-o /dev/stdout did not reach the shell's file"
if [ ! -L /dev/stdout ]; then
  fail "/dev/stdout was replaced by a regular file (restored)"
  [ "$(id -u)" = 0 ] && rm -f /dev/stdout && ln -s /proc/self/fd/1 /dev/stdout
fi
"$exe" refine "$tmp/torus.obj" -o /dev/null --scheme cc --levels 1 || fail "refine into /dev/null"
[ -c /dev/null ] || fail "/dev/null is no longer a character device"
printf 'mine\n' > "$nodes/ro.obj"
chmod 444 "$nodes/ro.obj"
"$exe" refine "$tmp/torus.obj" -o "$nodes/ro.obj" --scheme cc --levels 1 2> "$tmp/err.txt" && fail "a read-only output was replaced"
grep -q "ro.obj: cannot write: the file is read-only" "$tmp/err.txt" || fail "read-only output: $(cat "$tmp/err.txt")"
[ "$(cat "$nodes/ro.obj")" = "mine" ] || fail "the read-only output changed"

# Exports are made before the output is opened: a refusal (here a tessellation over the memory
# budget) is what the user sees even where the path is bad too, and a FIFO or /dev/stdout with a
# log behind it is never opened (it would block, or truncate the log) for a refused export.
"$exe" shape globe -o "$tmp/globe.obj" || fail "shape globe"
refused() { "$exe" export "$tmp/globe.obj" --scheme c2ps --level 3 --samples 64 --memory-budget 30M "$@"; }
refused -o "$tmp/no/such/dir/out.ply" 2> "$tmp/err.txt"
[ $? -eq 1 ] && grep -q "over the memory budget" "$tmp/err.txt" || fail "bad path and budget: $(cat "$tmp/err.txt")"
mkfifo "$tmp/fifo.ply"
timeout 20 "$exe" export "$tmp/globe.obj" --scheme c2ps --level 3 --samples 64 --memory-budget 30M -o "$tmp/fifo.ply" \
  2> "$tmp/err.txt"
[ $? -eq 1 ] && grep -q "over the memory budget" "$tmp/err.txt" || fail "a refused export opened a FIFO: $(cat "$tmp/err.txt")"
printf 'earlier lines\n' > "$tmp/log.txt"
refused -o /dev/stdout --format ply >> "$tmp/log.txt" 2> /dev/null
[ "$(cat "$tmp/log.txt")" = "earlier lines" ] || fail "a refused export to /dev/stdout truncated the log"

echo "atomic_output: $failures failures"
[ $failures -eq 0 ]
