#!/usr/bin/env bash
# bench --adaptive: the fields the README names, and the cost rule: around a valence-64 pole the
# feature-adaptive level 10 of RTS, BPS and Catmull-Clark holds fewer faces (all levels together)
# than the same scheme's uniform level 5 has at its finest
# (C2PS doubles the polar valence each level, so its rings alone outgrow that: not claimed).
# Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
field() { python3 -c "import json,sys; print(json.load(sys.stdin)['$1'])"; }

"$exe" shape cap --valence 64 --links 6 -o "$tmp/cap64.obj"
for scheme in rts bps cc; do
  uniform=$("$exe" bench "$tmp/cap64.obj" --scheme $scheme --levels 5 --reps 1 --json | field out_faces)
  json=$("$exe" bench "$tmp/cap64.obj" --scheme $scheme --levels 10 --adaptive --edit --reps 1 --json)
  for key in topology_ms positions_ms patches_ms patches peak_rss_mb edit_ms total_faces made_ahead_ms level_up_made_ahead_ms; do
    echo "$json" | field $key > /dev/null || fail "$scheme: no $key in $json"
  done
  faces=$(echo "$json" | field total_faces)
  [ "$faces" -lt "$uniform" ] || fail "$scheme level 10 adaptive holds $faces faces, uniform level 5 has $uniform"
done
# The adaptive and uniform paths extract the same number of patches.
a=$("$exe" bench "$tmp/cap64.obj" --scheme c2ps --levels 3 --adaptive --reps 1 --json | field patches)
u=$("$exe" bench "$tmp/cap64.obj" --scheme c2ps --levels 3 --reps 1 --json | field patches)
[ "$a" -eq "$u" ] || fail "c2ps level 3: $a adaptive patches, $u uniform"
# A level the viewer does not offer (its cap is 24): the bench still times its own path and says why
# it did not time the viewer's step.
"$exe" shape cap --valence 7 --links 3 -o "$tmp/cap7.obj"
json=$("$exe" bench "$tmp/cap7.obj" --scheme rts --levels 25 --adaptive --reps 1 --json) || fail "rts level 25: bench failed"
echo "$json" | python3 -c "import json,sys; d=json.load(sys.stdin); assert d['made_ahead_ms'] is None and 'refused' in d['viewer_step'] and d['patches'] > 0, d" \
  || fail "rts level 25: $json"
# --edit without --adaptive is a usage error.
set +e
"$exe" bench "$tmp/cap64.obj" --scheme cc --levels 1 --edit > /dev/null 2>&1
rc=$?
set -e
[ $rc -eq 2 ] || fail "--edit without --adaptive: exit $rc"
echo ok
