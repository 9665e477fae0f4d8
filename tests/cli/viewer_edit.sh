#!/usr/bin/env bash
# `polarview view --frames N --stats --edit`: the frames drag a control vertex of the default model
# through the viewer's real input path, and the stats JSON gains "edit" with the medians of the
# positions-only updates (refinement positions, patch extraction, upload); --edit without --frames is
# a usage error. Usage: bash viewer_edit.sh <polarview-exe> <repo>. Needs X: re-runs under Xvfb.
set -u
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

(cd "$work" && "$exe" view --level 2 --scheme c2ps,cc --frames 6 --stats --edit --hidden --size 800x500) > "$work/stats.json" 2> "$work/err.txt" ||
  fail "view --edit exited with $?: $(cat "$work/err.txt")"
python3 - "$work/stats.json" <<'PY' || fail "view --edit stats: $(cat "$work/stats.json")"
import json, sys
d = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
e = d["edit"]
assert e["frames"] == 6 and e["views"] == 2, e
for key in ("median_ms", "positions_ms", "patches_ms", "upload_ms"):
    assert e[key] > 0, (key, e)
assert e["positions_ms"] + e["patches_ms"] + e["upload_ms"] <= 1.5 * e["median_ms"] + 0.1, e
PY
# Nothing written: the edit stays in memory.
[ -z "$(ls -A "$work" | grep -v -e stats.json -e err.txt)" ] || fail "view --edit wrote files: $(ls "$work")"

"$exe" view --edit --hidden > /dev/null 2> "$work/usage.txt"
[ $? -eq 2 ] || fail "--edit without --frames is not a usage error"
grep -q -- "--edit needs --frames" "$work/usage.txt" || fail "no message for --edit without --frames: $(cat "$work/usage.txt")"

[ "$failures" -eq 0 ] || exit 1
echo "viewer_edit: ok"
