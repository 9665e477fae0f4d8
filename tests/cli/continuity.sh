#!/usr/bin/env bash
# continuity: the JSON report's shape, C2PS's polar seams G1 (normals to round-off) where
# Catmull-Clark's end caps around the same pole bend the normal, and bad input refused in one line.
# Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for scheme in c2ps cc; do
  "$exe" continuity "$root/assets/default.obj" --scheme $scheme --level 3 --json > "$tmp/$scheme.json"
done
python3 - "$tmp/c2ps.json" "$tmp/cc.json" <<'PY'
import json, sys
c2ps, cc = (json.load(open(p)) for p in sys.argv[1:3])
seam_keys = {"kind", "count", "t_junctions", "max_position_gap", "max_normal_angle", "max_curvature_jump",
             "max_gaussian_jump", "max_mean_jump"}
for d, scheme in ((c2ps, "c2ps"), (cc, "cc")):
    assert set(d) == {"seams", "boundary_sides", "max_abs_gaussian", "max_abs_mean", "box_diagonal", "samples",
                      "scheme", "level"}, d.keys()
    assert d["scheme"] == scheme and d["level"] == 3 and d["boundary_sides"] == 0, d
    assert d["max_abs_gaussian"] > 1 and d["max_abs_mean"] > 1, d
    assert d["samples"] == 8 and 4 < d["box_diagonal"] < 5, d  # the default K; the mushroom's diagonal
    for s in d["seams"]:
        assert set(s) == seam_keys, s
        assert s["count"] > 0 and 0 <= s["t_junctions"] <= s["count"], s
        assert s["max_curvature_jump"] == max(s["max_gaussian_jump"], s["max_mean_jump"]), s
        assert s["max_position_gap"] < 1e-9, s  # watertight
kinds = lambda d: {s["kind"]: s for s in d["seams"]}
# The mushroom: a valence-12 pole on a stem with four valence-3 Catmull-Clark vertices.
k2, kc = kinds(c2ps), kinds(cc)
assert set(k2) == {"regular", "ring-ring", "ring-cap", "cap-cap", "end-cap", "regular-ring"}, k2.keys()
assert set(kc) == {"regular", "end-cap"}, kc.keys()
for kind in ("regular", "ring-ring", "ring-cap", "cap-cap", "regular-ring"):
    assert k2[kind]["max_normal_angle"] < 1e-9, k2[kind]
for kind in ("regular", "ring-ring", "cap-cap", "regular-ring"):
    assert k2[kind]["max_curvature_jump"] < 1e-10, k2[kind]
assert k2["ring-ring"]["t_junctions"] > 0  # C2PS doubles the columns ring by ring
# Both have the stem's end caps; Catmull-Clark's around the valence-12 vertex bend the normal more
# (degrees, not round-off), while its regular seams are C2.
assert kc["end-cap"]["max_normal_angle"] > max(1e-2, 2 * k2["end-cap"]["max_normal_angle"]), (kc, k2)
assert kc["end-cap"]["count"] > k2["end-cap"]["count"], (kc, k2)
assert kc["regular"]["max_normal_angle"] < 1e-9 and kc["regular"]["max_curvature_jump"] < 1e-10, kc
PY

# The text table: one row per kind, the boundary line.
"$exe" continuity "$root/assets/cap12_paraboloid.obj" --scheme rts --level 2 --samples 4 > "$tmp/text.txt"
for kind in regular ring-ring ring-cap cap-cap regular-ring; do
  grep -q "^  $kind " "$tmp/text.txt" || fail "no $kind row: $(cat "$tmp/text.txt")"
done
grep -q "boundary sides (no partner): 12$" "$tmp/text.txt" || fail "boundary sides: $(cat "$tmp/text.txt")"

# Bad input: one line naming the file, exit 1; usage errors exit 2.
set +e
"$exe" continuity "$tmp/missing.obj" --scheme c2ps --level 2 > "$tmp/out" 2> "$tmp/err"; rc=$?
set -e
[ $rc -eq 1 ] || fail "missing file: exit $rc"
[ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -q "missing.obj" "$tmp/err" || fail "missing file: $(cat "$tmp/err")"
[ ! -s "$tmp/out" ] || fail "missing file printed: $(cat "$tmp/out")"
printf 'v 0 0 0\nv 1 0 0\nf 1 2 3\n' > "$tmp/bad.obj"
set +e
"$exe" continuity "$tmp/bad.obj" --scheme c2ps --level 2 --json > "$tmp/out" 2> "$tmp/err"; rc=$?
set -e
[ $rc -eq 1 ] && grep -q "bad.obj:3" "$tmp/err" && [ ! -s "$tmp/out" ] || fail "bad face: exit $rc, $(cat "$tmp/err")"
for args in "--level 2" "--scheme c2ps" "--scheme c2ps --level 2 --samples 0"; do
  set +e
  "$exe" continuity "$root/assets/default.obj" $args > /dev/null 2> "$tmp/err"; rc=$?
  set -e
  [ $rc -eq 2 ] || fail "continuity $args: exit $rc, $(cat "$tmp/err")"
done
# A model of 1e-300: curvature past double's range: refused in one line, nothing on stdout.
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2*1e-300, $3*1e-300, $4*1e-300; next} {print}' \
  "$root/assets/default.obj" > "$tmp/tiny.obj"
set +e
"$exe" continuity "$tmp/tiny.obj" --scheme c2ps --level 1 --json > "$tmp/out" 2> "$tmp/err"; rc=$?
set -e
[ $rc -eq 1 ] || fail "tiny: exit $rc"
[ ! -s "$tmp/out" ] || fail "tiny: printed $(cat "$tmp/out")"
grep -q "tiny.obj: the model spans .* below 1e-150" "$tmp/err" || fail "tiny: $(cat "$tmp/err")"
echo "continuity: ok"
