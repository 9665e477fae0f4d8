#!/usr/bin/env bash
# The command-line contract: refine writes the level-L mesh, info/pole/bench print what the
# README says, usage errors exit 2. Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py() { python3 -c "$@"; }

"$exe" shape globe --valence 8 --links 5 -o "$tmp/globe.obj"
"$exe" shape mushroom --valence 12 -o "$tmp/mushroom.obj"

# refine: C2PS on the globe: faces = 4 per quad corner... count faces and the pole valence 8 * 2^L.
"$exe" refine "$tmp/globe.obj" -o "$tmp/g2.obj" --scheme c2ps --levels 2
faces=$(grep -c '^f ' "$tmp/g2.obj")
verts=$(grep -c '^v ' "$tmp/g2.obj")
# level 0: 32 quads + 16 triangles. Level 1: 32*4 + 16*3 quads, 2*8 of them (at the poles) split in
# two: 160 quads + 32 triangles. Level 2: 160*4 + 32*3, plus 2*16 splits.
[ "$faces" -eq $((160*4 + 32*3 + 2*16)) ] || fail "c2ps level-2 globe has $faces faces"
# coordinates round-trip doubles (the shortest decimal of each): refined points need 15+ digits somewhere
grep -qE '^v -?[0-9]\.[0-9]{15,}' "$tmp/g2.obj" || fail "coordinates are not written with full precision"
# the refined mesh is itself a valid mesh whose poles have valence 32
"$exe" info "$tmp/g2.obj" --json > "$tmp/info.json"
py "import json; d=json.load(open('$tmp/info.json')); v=[p['valence'] for p in d['poles'] if p['refinable']]; assert v==[32,32], v; assert d['vertices']==$verts"

# rts on a globe is radial: valence stays, faces double per level
"$exe" refine "$tmp/globe.obj" -o "$tmp/r3.obj" --scheme rts --levels 3
[ "$(grep -c '^f ' "$tmp/r3.obj")" -eq $(( (32+16) * 8 )) ] || fail "rts globe faces"
"$exe" info "$tmp/r3.obj" --json | py "import json,sys; d=json.load(sys.stdin); assert [p['valence'] for p in d['poles']]==[8,8]"

# cc equals plain Catmull-Clark counts: every face becomes 4^L quads... (triangles give 3 quads first)
"$exe" refine "$tmp/mushroom.obj" -o "$tmp/cc1.obj" --scheme cc --levels 1
[ "$(grep -c '^f ' "$tmp/cc1.obj")" -eq $((12*3 + 105*4)) ] || fail "cc level-1 face count"

# info names the pole and the extraordinary vertices
"$exe" info "$tmp/mushroom.obj" --json | py "
import json,sys; d=json.load(sys.stdin)
assert d['poles'][0]['vertex']==0 and d['poles'][0]['valence']==12 and d['poles'][0]['regular_links']==8
assert sum(1 for x in d['extraordinary_vertices'] if x['valence']==3)==4
assert d['boundary_loops']==0"

# pole: paraboloid cap z = r^2/2 sampled at the links: K = 1 at the apex; JSON shape as documented
"$exe" shape cap --valence 16 --links 4 -o "$tmp/cap.obj"
"$exe" pole "$tmp/cap.obj" --json | py "
import json,sys; d=json.load(sys.stdin); p=d['poles'][0]
assert p['vertex']==0 and p['valence']==16 and len(p['p'])==6 and len(p['limit'])==3
assert abs(p['normal'][2]-1)<1e-12, p['normal']
# the sampled paraboloid has radial spacing 1/4: curvature 1 with an exact Greville shift (constant)
assert abs(p['gaussian_curvature']-1)<1e-9, p['gaussian_curvature']
assert abs(p['mean_curvature']-1)<1e-9, p['mean_curvature']"
# BPS is C1 at the pole: no curvature there
"$exe" pole "$tmp/cap.obj" --scheme bps --json | py "import json,sys; p=json.load(sys.stdin)['poles'][0]; assert p['gaussian_curvature'] is None"

# bench prints one JSON line with the documented fields
"$exe" bench "$tmp/mushroom.obj" --scheme c2ps --levels 2 --reps 1 --json | py "
import json,sys; d=json.loads(sys.stdin.read())
for k in ['topology_ms','positions_ms','patches_ms','out_vertices','out_faces','patches']: assert k in d, k
assert d['patches']>0 and d['out_faces']>0"

# pole --rings: curvature ring by ring. C2PS doubles the valence and converges to the pole's K;
# RTS keeps the valence, its K keeps an angular spread (the text says so); BPS has no K0 to compare.
"$exe" shape cap --valence 12 --links 6 -o "$tmp/cap12.obj"
"$exe" pole "$tmp/cap12.obj" --scheme c2ps --rings 10 --json | py "
import json,sys; d=json.loads(sys.stdin.read()); r=d['poles'][0]['rings']
assert [x['m'] for x in r]==list(range(1,11)), r
assert [x['valence'] for x in r]==[12*2**m for m in range(1,11)]
dk=[x['max_abs_dK'] for x in r]; assert all(dk[m] < dk[m-1] for m in range(4,10)), dk
assert dk[-1] < 1e-4, dk
for k in ['K_min','K_max','max_abs_dH','H_min','H_max']: assert k in r[0], k"
"$exe" pole "$tmp/cap12.obj" --scheme rts --rings 10 --json | py "
import json,sys; r=json.loads(sys.stdin.read())['poles'][0]['rings']
assert all(x['valence']==12 for x in r); assert r[-1]['K_max']-r[-1]['K_min'] > 1e-3, r[-1]"
"$exe" pole "$tmp/cap12.obj" --scheme rts | grep -q "K depends on the direction" || fail "pole rts: no direction note"
"$exe" pole "$tmp/cap12.obj" --scheme bps --rings 3 --json | py "
import json,sys; r=json.loads(sys.stdin.read())['poles'][0]['rings']; assert r[0]['max_abs_dK'] is None, r"

# spectrum: Table 1 for RTS at valence 7, Catmull-Clark's 1, 1/2, 1/2, 1/4 at valence 4
"$exe" spectrum --scheme rts --valence 7 --json | py "
import json,sys; d=json.loads(sys.stdin.read()); v=[e['re'] for e in d['eigenvalues'][:6]]
assert all(abs(a-b)<1e-12 for a,b in zip(v,[1,.5,.5,.25,.25,.25])), v; assert d['size']==42"
"$exe" spectrum --scheme cc --valence 4 --count 4 --json | py "
import json,sys; v=[e['re'] for e in json.loads(sys.stdin.read())['eigenvalues']]
assert all(abs(a-b)<1e-12 for a,b in zip(v,[1,.5,.5,.25])), v"
# spectrum --vectors: per eigenvalue v and w in the matrix's order (q_ij at 6j+i), A v = lambda v
# to round-off, w_k^T v_l = delta_kl; RTS's 1/2 pair is i cos(2 pi j/n), i sin(2 pi j/n) (Table 1, (14))
"$exe" spectrum --scheme rts --valence 7 --count 6 --vectors --json | py "
import json,math,sys; d=json.loads(sys.stdin.read()); e=d['eigenvalues']; n=7
assert [x['mode'] for x in e]==['single','cos','sin','single','cos','sin'], [x['mode'] for x in e]
assert all(len(x['right'])==6*n and len(x['left'])==6*n and x['residual']<1e-12 for x in e)
for k in range(6):
    for l in range(6):
        dot=sum(a*b for a,b in zip(e[k]['left'],e[l]['right'])); assert abs(dot-(k==l))<1e-12, (k,l,dot)
for k,f in ((1,math.cos),(2,math.sin)):
    v=e[k]['right']; c=v[6*0+5]/5 if k==1 else v[6*1+5]/(5*math.sin(2*math.pi/n))
    assert all(abs(v[6*j+i]-c*i*f(2*math.pi*j/n))<1e-12 for i in range(6) for j in range(n)), k"
"$exe" spectrum --scheme cc --valence 5 --count 3 --vectors --json | py "
import json,sys; e=json.loads(sys.stdin.read())['eigenvalues']
assert all(len(x['right'])==11 and x['residual']<1e-12 for x in e); assert abs(e[0]['left'][0]-25/50)<1e-12"

# spectrum --scheme c2ps: Lemma 5 (eigencoefficients scale by lambda_k^m) and (30) (O(8^-m), 0 on links 0, 1)
"$exe" spectrum --scheme c2ps --valence 6 --steps 6 --json | py "
import json,sys; s=json.loads(sys.stdin.read())['steps']; assert [x['valence'] for x in s]==[12,24,48,96,192,384], s
assert all(x['coefficient_error']<1e-12 and x['deviation_links01']<1e-12 for x in s), s
assert 6 < s[4]['deviation']/s[5]['deviation'] < 8.5, s"

# one scheme-name parser for every command: refine takes the spellings render and view take
"$exe" refine "$tmp/globe.obj" -o "$tmp/cc.obj" --scheme cc --levels 1
"$exe" refine "$tmp/globe.obj" -o "$tmp/catmull.obj" --scheme catmull-clark --levels 1
cmp -s "$tmp/cc.obj" "$tmp/catmull.obj" || fail "refine --scheme catmull-clark should refine as --scheme cc"
"$exe" refine "$tmp/globe.obj" -o "$tmp/c2psu.obj" --scheme C2PS-Uniform --levels 1
"$exe" refine "$tmp/globe.obj" -o "$tmp/c2ps-u.obj" --scheme c2ps-u --levels 1
cmp -s "$tmp/c2psu.obj" "$tmp/c2ps-u.obj" || fail "refine --scheme C2PS-Uniform should refine as --scheme c2ps-u"

# usage errors exit 2 with the usage; an unknown scheme too
set +e
"$exe" refine "$tmp/globe.obj" --levels 1 >/dev/null 2>&1; [ $? -eq 2 ] || fail "missing -o should exit 2"
"$exe" refine "$tmp/globe.obj" -o "$tmp/x.obj" --scheme loop --levels 1 2>/dev/null; [ $? -eq 2 ] || fail "unknown scheme should exit 2"
"$exe" frobnicate 2>/dev/null; [ $? -eq 2 ] || fail "unknown command should exit 2"
"$exe" spectrum --scheme c2ps --valence 6 --vectors 2>/dev/null; [ $? -eq 2 ] || fail "spectrum c2ps --vectors should exit 2"
"$exe" spectrum --scheme rts --valence 4 2>/dev/null; [ $? -eq 2 ] || fail "spectrum rts n=4 should exit 2"
"$exe" pole "$tmp/cap12.obj" --rings 0 2>/dev/null; [ $? -eq 2 ] || fail "pole --rings 0 should exit 2"
"$exe" pole "$tmp/cap12.obj" --scheme c2ps --rings 20 2>/dev/null; [ $? -eq 1 ] || fail "pole: C2PS valence over 2^18 (a limit of the input) should exit 1"
# a level that would not fit in memory: exit 1, one line, no output file
"$exe" refine "$tmp/mushroom.obj" -o "$tmp/huge.obj" --scheme c2ps --levels 30 2>"$tmp/err"; rc=$?
set -e
[ $rc -eq 1 ] || fail "huge level exit $rc"
[ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "huge level: not one line"
grep -q "^polarview: .*mushroom.obj" "$tmp/err" || fail "huge level: no file name"
[ ! -e "$tmp/huge.obj" ] || fail "huge level left an output file"
# the top-level usage lists every option `render` and `view` take (their own usage, printed on a
# usage error)
help="$("$exe" help)"
for cmd in render view; do
  own="$("$exe" "$cmd" /nonexistent.obj --frobnicate 2>&1 || true)"
  grep -q "^usage: polarview $cmd" <<< "$own" || fail "$cmd: no usage on a usage error"
  for opt in $(printf '%s\n' "$own" | sed -n '/^usage:/,$p' | grep -o -- '--[a-z-]*' | sort -u); do
    grep -q -- "$opt" <<< "$help" || fail "'polarview help' lacks $cmd's $opt"  # (no pipe: grep -q stops early)
  done
done
# the memory budget is bytes: a refusal comes at once, in one line, and names the deepest level that fits
"$exe" shape cube -o "$tmp/cube.obj"
set +e
"$exe" refine "$tmp/cube.obj" -o "$tmp/cube11.obj" --scheme cc --levels 11 --memory-budget 1G 2>"$tmp/err"; rc=$?
"$exe" refine "$tmp/cube.obj" -o "$tmp/cube2.obj" --scheme cc --levels 2 --memory-budget 1X 2>/dev/null; rc2=$?
set -e
[ $rc -eq 1 ] || fail "memory budget: exit $rc"
[ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "memory budget: not one line: $(cat "$tmp/err")"
grep -q "cube.obj: level 11 would need about .* over the memory budget of .*: level 9 fits" "$tmp/err" || fail "memory budget message: $(cat "$tmp/err")"
[ ! -e "$tmp/cube11.obj" ] || fail "memory budget: an output file was left"
[ $rc2 -eq 2 ] || fail "--memory-budget 1X should be a usage error"
# RTS on a globe grows x2 a level: level 12 fits 200 MB
"$exe" refine "$tmp/globe.obj" -o "$tmp/globe12.obj" --scheme rts --levels 12 --memory-budget 200M || fail "rts level 12 in 200M"
echo "commands: ok"
