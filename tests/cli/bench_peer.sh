#!/usr/bin/env bash
# bench compares timings with its OpenSubdiv peer only where both computed the same surface: the
# peer computes Catmull-Clark only, so speed-ups are printed for cc (and for schemes that refine no
# pole of the mesh) with equal face counts, and never where a polar scheme refined a pole.
# Passes with or without OpenSubdiv (then there is no peer and never a speed-up).
# Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$exe" shape cap --valence 16 --links 4 -o "$tmp/cap.obj"
"$exe" shape torus --valence 8 --links 6 -o "$tmp/torus.obj"
"$exe" shape cube -o "$tmp/cube.obj"

# Is there a peer in this build?
"$exe" bench "$tmp/torus.obj" --scheme cc --levels 1 --reps 1 --json > "$tmp/probe.json"
peer=$(python3 -c "import json; print(int('peer' in json.load(open('$tmp/probe.json'))))")

# bench_check FILE SCHEME LEVELS EXPECT: EXPECT is "compared" or "not-compared".
bench_check() {
  "$exe" bench "$1" --scheme "$2" --levels "$3" --reps 1 --json > "$tmp/b.json"
  "$exe" bench "$1" --scheme "$2" --levels "$3" --reps 1 > "$tmp/b.txt"
  python3 -c "
import json; d=json.load(open('$tmp/b.json')); text=open('$tmp/b.txt').read()
what='$1 $2'; expect='$4'; peer=$peer
speedups=[k for k in d if k.endswith('speedup')]
assert isinstance(d['compared'], bool) and d['comparison'], what
if not peer:
    assert 'peer' not in d and not d['compared'] and not speedups, (what, d)
elif expect=='compared':
    assert d['compared'] and speedups==['topology_speedup','positions_speedup','speedup'], (what, d)
    assert d['peer']['out_faces']==d['out_faces'], (what, d)
    assert d['comparison'].startswith('same surface: Catmull-Clark'), (what, d['comparison'])
    assert 'not compared' not in d['peer']['what'] and 'speed-up' in text, (what, d, text)
else:
    assert not d['compared'] and not speedups, (what, d)
    assert 'not compared' in d['peer']['what'] and 'Catmull-Clark' in d['peer']['what'], (what, d['peer'])
    assert d['peer']['out_faces']!=d['out_faces'], (what, d)
    assert 'different surfaces' in d['comparison'], (what, d['comparison'])
    assert 'speed-up' not in text, (what, text)
" || fail "bench $1 --scheme $2 --levels $3"
}

# Polar schemes on a cap refine its pole: a different surface from OpenSubdiv's.
bench_check "$tmp/cap.obj" rts 3 not-compared
bench_check "$tmp/cap.obj" rts-u 2 not-compared
bench_check "$tmp/cap.obj" bps 2 not-compared
bench_check "$tmp/cap.obj" c2ps 2 not-compared
# Catmull-Clark is the peer's surface, on any mesh; a polar scheme on a mesh without poles too.
bench_check "$tmp/cap.obj" cc 2 compared
bench_check "$tmp/torus.obj" cc 3 compared
bench_check "$tmp/cube.obj" cc 3 compared
bench_check "$tmp/torus.obj" rts 2 compared
bench_check "$tmp/cube.obj" c2ps 2 compared

# --vs-opensubdiv checks Catmull-Clark's points against OpenSubdiv's; elsewhere it says why not.
# Every uniform bench reports its peak RSS and positions' bandwidth beside a triad loop's.
if [ "$peer" = 1 ]; then
  "$exe" bench "$tmp/torus.obj" --scheme cc --levels 3 --reps 1 --vs-opensubdiv --json > "$tmp/v.json" || fail "vs-opensubdiv torus cc"
  "$exe" bench "$tmp/cap.obj" --scheme c2ps --levels 2 --reps 1 --vs-opensubdiv --json > "$tmp/p.json" || fail "vs-opensubdiv cap c2ps"
  python3 -c "
import json; v=json.load(open('$tmp/v.json')); p=json.load(open('$tmp/p.json'))
assert v['vs_opensubdiv']['checked'] and v['vs_opensubdiv']['equal'] and v['vs_opensubdiv']['max_difference'] < 1e-12, v
assert v['speedup'] > 0 and v['peak_rss_mb'] > 0 and v['triad_gbs'] > 0 and v['positions_gbs'] > 0, v
assert not p['vs_opensubdiv']['checked'] and 'different surfaces' in p['vs_opensubdiv']['why'], p
assert not any(k.endswith('speedup') for k in p), p
" || fail "bench --vs-opensubdiv"
else
  if "$exe" bench "$tmp/torus.obj" --scheme cc --levels 1 --reps 1 --vs-opensubdiv > /dev/null 2>&1; then
    fail "--vs-opensubdiv without OpenSubdiv must fail"
  fi
fi
echo "bench_peer: ok (peer: $peer)"
