#!/usr/bin/env bash
# info tells real poles (configurations a polar scheme refines) apart from vertices that only look
# polar (a fan of triangles whose ring is not 4-valent vertices between quads): those are rejected
# candidates with a reason, never counted or listed as poles. Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py() { python3 -c "$@"; }

# Triangle meshes where every vertex is a candidate: an icosahedron (its fans' rims are 5-valent)
# and an octahedron (4-valent rims, but ringed by triangles, no quads). Then both next to a globe
# (shifted apart) in one file.
"$exe" shape globe --valence 8 --links 3 -o "$tmp/globe.obj"
py "
import itertools, math
def hull(points):  # the faces of a convex polyhedron whose edges all have the shortest length
    d = min(math.dist(a, b) for a, b in itertools.combinations(points, 2))
    adj = lambda a, b: abs(math.dist(points[a], points[b]) - d) < 1e-9
    faces = []
    for a, b, c in itertools.combinations(range(len(points)), 3):
        if adj(a, b) and adj(b, c) and adj(a, c):
            u = [points[b][k] - points[a][k] for k in range(3)]
            v = [points[c][k] - points[a][k] for k in range(3)]
            n = [u[1]*v[2]-u[2]*v[1], u[2]*v[0]-u[0]*v[2], u[0]*v[1]-u[1]*v[0]]
            faces.append((a, b, c) if sum(n[k]*points[a][k] for k in range(3)) > 0 else (a, c, b))
    return faces
phi = (1 + 5 ** 0.5) / 2
ico = [p for s in itertools.product((-1, 1), repeat=2) for p in ((0, s[0], s[1]*phi), (s[0], s[1]*phi, 0), (s[1]*phi, 0, s[0]))]
octa = [tuple(s * (k == axis) for k in range(3)) for axis in range(3) for s in (-1, 1)]
def write(path, parts):
    out, faces, base = [], [], 0
    for points, tris in parts:
        out += ['v %.17g %.17g %.17g' % p for p in points]
        faces += ['f ' + ' '.join(str(base + i + 1) for i in t) for t in tris]
        base += len(points)
    open(path, 'w').write('\n'.join(out + faces) + '\n')
lines = open('$tmp/globe.obj').read().split('\n')
globe = ([tuple(map(float, l.split()[1:])) for l in lines if l.startswith('v ')],
         [tuple(int(i) - 1 for i in l.split()[1:]) for l in lines if l.startswith('f ')])
shift = lambda pts, x: [(p[0] + x, p[1], p[2]) for p in pts]
write('$tmp/ico.obj', [(ico, hull(ico))])
write('$tmp/octa.obj', [(octa, hull(octa))])
write('$tmp/all.obj', [globe, (shift(ico, 5), hull(ico)), (shift(octa, 10), hull(octa))])
# A cone without a base (Blender's cone, cap fill none): a 32-valent fan whose rim is a boundary,
# its tip the last vertex, after the icosahedron and the octahedron.
cone = [(math.cos(2 * math.pi * i / 32), math.sin(2 * math.pi * i / 32), 0.0) for i in range(32)] + [(0.0, 0.0, 2.0)]
write('$tmp/cone.obj', [(ico, hull(ico)), (shift(octa, 5), hull(octa)), (shift(cone, 10), [(i, (i + 1) % 32, 32) for i in range(32)])])"

# The icosahedron: no pole, 12 rejected candidates whose 1-link is not 4-valent.
"$exe" info "$tmp/ico.obj" > "$tmp/ico.txt"
grep -qx "poles: 0" "$tmp/ico.txt" || fail "icosahedron: $(grep poles "$tmp/ico.txt")"
grep -q "^rejected pole candidates: 12 (reasons: 12 a 1-link vertex is not 4-valent)" "$tmp/ico.txt" ||
  fail "icosahedron: $(grep rejected "$tmp/ico.txt")"
"$exe" info "$tmp/ico.obj" --json | py "
import json,sys; d=json.load(sys.stdin)
assert d['faces']==20 and d['poles']==[], d['poles']
r=d['rejected_candidates']
assert sorted(x['vertex'] for x in r)==list(range(12)), r
assert all(x['reason']=='link1_not_4_valent' and x['valence']==5 and '5-valent' in x['detail'] for x in r), r
assert d['rejected_reasons']=={'link1_not_4_valent':12}, d['rejected_reasons']
assert not any(x['pole'] for x in d['extraordinary_vertices'])"

# All three in one file: the globe's two poles are the poles, the 18 others are rejected.
"$exe" info "$tmp/all.obj" > "$tmp/all.txt"
grep -qx "poles: 2" "$tmp/all.txt" || fail "globe + icosahedron + octahedron: $(grep poles "$tmp/all.txt")"
grep -q "^rejected pole candidates: 18 (reasons: 12 a 1-link vertex is not 4-valent; 6 a 1-link vertex is not between 2 triangles and 2 quads)" "$tmp/all.txt" ||
  fail "globe + icosahedron + octahedron: $(grep rejected "$tmp/all.txt")"
"$exe" info "$tmp/all.obj" --json | py "
import json,sys; d=json.load(sys.stdin)
p=d['poles']
assert [x['valence'] for x in p]==[8,8] and all(x['refinable'] for x in p), p
assert p[0]['opposite_pole']==p[1]['vertex']
poles={x['vertex'] for x in p}
r=d['rejected_candidates']
assert len(r)==18 and poles.isdisjoint(x['vertex'] for x in r)
assert d['rejected_reasons']=={'link1_not_4_valent':12,'link1_not_2_triangles_2_quads':6}, d['rejected_reasons']
assert all(x['valence']==4 for x in r if x['reason']=='link1_not_2_triangles_2_quads')
assert {x['vertex'] for x in d['extraordinary_vertices'] if x['pole']}==poles"

# Grouped by reason, the nearest candidates first: the cone's 32-valent tip (vertex 50) heads the
# list though its id is the last; then the icosahedron's 5-valent, then the octahedron's 4-valent
# fans, at most 5 listed a reason.
"$exe" info "$tmp/cone.obj" > "$tmp/cone.txt"
grep -q "^rejected pole candidates: 19 (reasons: 1 a 1-link vertex is on a boundary; 12 a 1-link vertex is not 4-valent; 6 a 1-link vertex is not between 2 triangles and 2 quads)" "$tmp/cone.txt" ||
  fail "cone: $(grep rejected "$tmp/cone.txt")"
sed -n '/^rejected/,/^extraordinary/p' "$tmp/cone.txt" | sed '1d;$d' > "$tmp/groups.txt"
cat > "$tmp/expected.txt" <<'END'
  a 1-link vertex is on a boundary: 1 candidate, valence 32
    vertex 50 (valence 32): its 1-link vertex 18 is on a boundary
  a 1-link vertex is not 4-valent: 12 candidates, valence 5
    vertex 0 (valence 5): its 1-link has a 5-valent vertex (vertex 1)
END
head -4 "$tmp/groups.txt" | diff "$tmp/expected.txt" - || fail "cone: the groups' heads differ (above)"
grep -q "^    ... 7 more (info --json lists every one)" "$tmp/groups.txt" || fail "cone: the icosahedron's 12 not cut at 5"
grep -q "^  a 1-link vertex is not between 2 triangles and 2 quads: 6 candidates, valence 4$" "$tmp/groups.txt" || fail "cone: no octahedron group"
[ "$(grep -c "^    vertex" "$tmp/groups.txt")" -eq $((1 + 5 + 5)) ] || fail "cone: $(grep -c "^    vertex" "$tmp/groups.txt") candidates listed"
"$exe" info "$tmp/cone.obj" --json | py "
import json,sys; d=json.load(sys.stdin)
assert [x['vertex'] for x in d['rejected_candidates']]==list(range(18))+[50]  # the old field: all, by id
g=d['rejected_groups']
assert [(x['reason'],x['max_valence'],len(x['vertices'])) for x in g]==[('link1_on_boundary',32,1),('link1_not_4_valent',5,12),('link1_not_2_triangles_2_quads',4,6)], g
assert g[0]['vertices']==[50] and g[0]['words']=='a 1-link vertex is on a boundary'
assert g[1]['vertices']==list(range(12)) and g[2]['vertices']==list(range(12,18))"

# Real poles stay listed, with nothing rejected: the default globe and the built-in model.
"$exe" shape globe -o "$tmp/g.obj"
"$exe" info "$tmp/g.obj" > "$tmp/g.txt"
grep -qx "poles: 2" "$tmp/g.txt" || fail "globe: $(grep poles "$tmp/g.txt")"
if grep -q "rejected" "$tmp/g.txt"; then fail "globe: rejected candidates reported"; fi
"$exe" info "$root/assets/default.obj" --json | py "
import json,sys; d=json.load(sys.stdin)
assert [(x['vertex'],x['valence']) for x in d['poles']]==[(0,12)], d['poles']
assert d['rejected_candidates']==[] and d['rejected_reasons']=={}"
# pole at every scale the reader accepts: the rings' K scale by 1 / s^2 (computed unscaled, E G - F^2
# of a globe of 1e-80 underflowed to 0 and the rings read "0 .. 0"); the text says "undefined" where
# the JSON has null (it printed nan); a --rings limit that depends on the input is bad input (exit 1,
# FILE: reason), not a usage error.
"$exe" pole "$tmp/g.obj" --rings 2 --json > "$tmp/pole1.json"
for scale in 1e-150 1e-80 1e80 1e150; do
  awk -v s="$scale" '/^v /{printf "v %.17g %.17g %.17g\n", $2 * s, $3 * s, $4 * s; next} {print}' "$tmp/g.obj" > "$tmp/g$scale.obj"
  "$exe" pole "$tmp/g$scale.obj" --rings 2 --json | py "
import json,sys; s=$scale; one=json.load(open('$tmp/pole1.json'))['poles']; d=json.load(sys.stdin)['poles']
for a,b in zip(one,d):
  assert abs(b['gaussian_curvature']*s*s/a['gaussian_curvature']-1)<1e-9, (a['gaussian_curvature'], b['gaussian_curvature'])
  for ra,rb in zip(a['rings'],b['rings']):
    for key in ('K_min','K_max','max_abs_dK'):
      assert abs(rb[key]*s*s/ra[key]-1)<1e-9, (s, key, ra[key], rb[key])
    assert abs(rb['H_max']*s/ra['H_max']-1)<1e-9, (s, ra['H_max'], rb['H_max'])" || fail "pole --rings at scale $scale"
done
"$exe" pole "$tmp/g.obj" --scheme bps --rings 2 > "$tmp/bps.txt" || fail "pole --scheme bps"
! grep -q "nan" "$tmp/bps.txt" || fail "pole text prints nan: $(cat "$tmp/bps.txt")"
[ "$(grep -c "K undefined H undefined" "$tmp/bps.txt")" -eq 2 ] || fail "pole text: K not 'undefined' for BPS: $(head -1 "$tmp/bps.txt")"
[ "$(grep -c "^ *[12] *12  undefined" "$tmp/bps.txt")" -eq 4 ] || fail "pole text: ring rows not 'undefined' for BPS"
"$exe" shape cap --valence 5000 --links 2 -o "$tmp/cap5000.obj"
rc=0
"$exe" pole "$tmp/cap5000.obj" --rings 8 > "$tmp/out.txt" 2> "$tmp/err.txt" || rc=$?
[ $rc -eq 1 ] || fail "pole --rings over the valence limit: exit $rc (expected 1)"
[ "$(wc -l < "$tmp/err.txt")" -eq 1 ] && grep -q "^polarview: $tmp/cap5000.obj: --rings 8 would give C2PS a valence over 2^18 .*at most --rings 5$" "$tmp/err.txt" ||
  fail "pole --rings over the limit: $(head -3 "$tmp/err.txt")"
[ ! -s "$tmp/out.txt" ] || fail "pole --rings over the limit printed: $(head -2 "$tmp/out.txt")"
echo "info_poles: ok"
