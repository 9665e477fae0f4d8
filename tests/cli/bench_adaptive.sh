#!/usr/bin/env bash
# bench --adaptive: the fields the README names, and the cost rule: around a valence-64 pole the
# feature-adaptive level 10 of RTS, BPS and Catmull-Clark holds fewer faces (all levels together)
# than the same scheme's uniform level 5 has at its finest
# (C2PS doubles the polar valence each level, so its rings alone outgrow that: not claimed).
# With --vs-opensubdiv, OpenSubdiv's own feature-adaptive path runs beside it and makes as many
# patches (skipped, but --vs-opensubdiv must then fail, in a build without OpenSubdiv).
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
# --vs-opensubdiv: the peer's fields and ratios, and equal patch counts: a cap (an extraordinary
# vertex of valence 16 and a boundary) and a cube with a semi-sharp crease and a corner (sharpness
# decaying level by level), Catmull-Clark; C2PS on the cap refines the pole: not compared.
"$exe" shape cap --valence 16 --links 4 -o "$tmp/cap16.obj"
cube='v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n'
cube+='f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n'
printf "${cube}t crease 2/1/0 0 1 2.5\nt corner 1/1/0 6 1.5\n" > "$tmp/tagged.obj"
set +e
"$exe" bench "$tmp/cap16.obj" --scheme cc --levels 6 --adaptive --vs-opensubdiv --reps 2 --json > "$tmp/v.json" 2> "$tmp/v.err"
rc=$?
set -e
if [ $rc -eq 2 ] && grep -q "built without OpenSubdiv" "$tmp/v.err"; then
  echo "bench --adaptive --vs-opensubdiv: no OpenSubdiv in this build, peer checks skipped"
else
  [ $rc -eq 0 ] || fail "--adaptive --vs-opensubdiv on the cap: exit $rc $(cat "$tmp/v.err")"
  "$exe" bench "$tmp/tagged.obj" --scheme cc --levels 5 --adaptive --vs-opensubdiv --reps 2 --json > "$tmp/t.json" 2> /dev/null ||
    fail "--adaptive --vs-opensubdiv on the tagged cube"
  "$exe" bench "$tmp/cap16.obj" --scheme cc --levels 4 --adaptive --vs-opensubdiv --reps 1 > "$tmp/v.txt" || fail "text output"
  "$exe" bench "$tmp/cap16.obj" --scheme c2ps --levels 3 --adaptive --vs-opensubdiv --reps 1 --json > "$tmp/p.json" ||
    fail "--adaptive --vs-opensubdiv c2ps on the cap"
  python3 -c "
import json
for name in ('v', 't'):
    d = json.load(open('$tmp/' + name + '.json'))
    p = d['peer']
    for k in ('topology_ms', 'patches_ms', 'positions_ms', 'patches', 'total_faces', 'level_faces', 'peak_rss_mb'):
        assert k in p, (name, k, p)
    assert d['compared'] and d['patches_agree'] is True and p['patches'] == d['patches'] > 0, (name, d)
    for k in ('topology_speedup', 'patches_speedup', 'positions_speedup', 'speedup', 'faces_ratio'):
        assert d[k] > 0, (name, k, d)
    assert len(p['level_faces']) == len(d['level_faces']) == d['levels'] + 1, (name, d)
c = json.load(open('$tmp/p.json'))
assert not c['compared'] and 'different surfaces' in c['comparison'] and 'peer' not in c, c
assert not any(k.endswith('speedup') for k in c) and 'patches_agree' not in c, c
text = open('$tmp/v.txt').read()
assert 'opensubdiv-3.5 adaptive:' in text and '(agree)' in text and 'speed-up' in text, text
" || fail "bench --adaptive --vs-opensubdiv: $(cat "$tmp/v.json" "$tmp/t.json")"
fi
# The floor (bench_floor.h): the bytes each stage must move, recomputed here from what the bench
# reports (faces of each level: 4-byte indices; the patches' count), never above what was measured.
"$exe" bench "$tmp/cap64.obj" --scheme cc --levels 6 --adaptive --reps 3 --json > "$tmp/f.json" || fail "floor run"
python3 - "$tmp/f.json" "$tmp/cap64.obj" <<'PY' || fail "the floor: $(cat "$tmp/f.json")"
import json, sys
d = json.load(open(sys.argv[1]))
f = d["floor"]
assert f["triad_gbs_one_thread"] > 0.5 and f["triad_gbs_all_threads"] > 0.5 and f["threads"] >= 1, f
faces = d["level_faces"]
# Topology: each level >= 1 writes its quads' 4 indices and a parent per face, reads the parent's corners
# (Catmull-Clark: quads from level 1 on; level 0's corners as the file has them).
corners = [4 * n for n in faces]
corners[0] = sum(len(line.split()) - 1 for line in open(sys.argv[2]) if line.startswith("f "))
expected = sum(4 * (corners[m] + faces[m] + corners[m - 1]) for m in range(1, len(faces)))
assert abs(f["topology"]["bytes"] - expected) <= 1e-9 * expected, (f["topology"]["bytes"], expected)
assert f["patches"]["bytes"] > 400 * d["patches"], f
for stage in ("topology", "positions", "patches"):
    s = f[stage]
    assert 0 < s["fraction"] <= 1 and abs(s["floor_ms"] - s["bytes"] / (f["triad_gbs_all_threads"] * 1e6)) < 1e-9, (stage, s)
PY
# --edit without --adaptive is a usage error.
set +e
"$exe" bench "$tmp/cap64.obj" --scheme cc --levels 1 --edit > /dev/null 2>&1
rc=$?
set -e
[ $rc -eq 2 ] || fail "--edit without --adaptive: exit $rc"
echo ok
