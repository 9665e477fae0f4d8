#!/usr/bin/env bash
# The models in assets/ are what the commands in assets/README.md make: each is made again here and
# compared byte for byte (a change to a shape generator must ship its model again). The paper's
# figure inputs are the configurations the figures need: five valence-8 finger tips on a
# Catmull-Clark body (Fig. 2c), one valence-20 pole (Fig. 12); `shape valence20|fingertips` takes
# no --valence or --links (usage error, exit 2).
# Usage: bash shape_assets.sh <polarview-exe> <repo>
set -u
exe="$1"
repo="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# file: the shape arguments that make it (assets/README.md lists the same commands).
check() {  # file args...
  local file="$1"
  shift
  if ! "$exe" shape "$@" -o "$work/$file" > /dev/null 2> "$work/err.txt"; then
    fail "shape $*: $(cat "$work/err.txt")"
  elif ! cmp -s "$work/$file" "$repo/assets/$file"; then
    fail "assets/$file differs from what 'polarview shape $*' makes"
  fi
}
check default.obj mushroom --valence 12
check globe.obj globe --valence 16 --links 7
check fingertips.obj fingertips
check valence20.obj valence20
check convex16.obj cap --height convex --valence 16 --links 5
check cap6_paraboloid.obj cap --height paraboloid --valence 6
check cap6_saddle.obj cap --height saddle --valence 6
check cap8_paraboloid.obj cap --height paraboloid --valence 8
check cap6_cone.obj cap --height cone --valence 6
for height in paraboloid saddle monkey flat4 saddle4; do
  check "cap12_$height.obj" cap --height "$height" --valence 12
done
# A refined mesh: same faces, points to round-off (the refiner's summation order may change).
same_mesh() {  # a.obj b.obj
  python3 - "$1" "$2" <<'PY'
import sys
def read(path):
    points, faces = [], []
    for line in open(path):
        part = line.split()
        if part and part[0] == "v": points.append([float(x) for x in part[1:4]])
        elif part and part[0] == "f": faces.append(part[1:])
    return points, faces
(pa, fa), (pb, fb) = read(sys.argv[1]), read(sys.argv[2])
ok = fa == fb and len(pa) == len(pb) and all(abs(x - y) <= 1e-12 for p, q in zip(pa, pb) for x, y in zip(p, q))
sys.exit(0 if ok else 1)
PY
}
"$exe" shape cube -o "$work/cube.obj" > /dev/null &&
  "$exe" refine "$work/cube.obj" --scheme cc --levels 2 -o "$work/cube_cc2.obj" > /dev/null &&
  same_mesh "$work/cube_cc2.obj" "$repo/assets/cube_cc2.obj" || fail "assets/cube_cc2.obj differs from the refined cube"

# The figure inputs' poles, from info --json.
poles() {  # file -> "valence valence ..."
  "$exe" info "$1" --json | python3 -c 'import json, sys; print(" ".join(str(p["valence"]) for p in json.load(sys.stdin)["poles"]))'
}
[ "$(poles "$repo/assets/fingertips.obj")" = "8 8 8 8 8" ] || fail "fingertips.obj poles: $(poles "$repo/assets/fingertips.obj")"
[ "$(poles "$repo/assets/valence20.obj")" = "20" ] || fail "valence20.obj poles: $(poles "$repo/assets/valence20.obj")"
# The body of the hand is Catmull-Clark: its extraordinary vertices are not poles.
ev="$("$exe" info "$repo/assets/fingertips.obj" --json | python3 -c 'import json, sys; print(len(json.load(sys.stdin)["extraordinary_vertices"]))')"
[ "$ev" -gt 20 ] || fail "fingertips.obj has $ev extraordinary vertices, expected the body's (> 20)"

for name in valence20 fingertips; do
  "$exe" shape "$name" --valence 5 -o "$work/x.obj" > /dev/null 2>&1
  rc=$?
  [ $rc -eq 2 ] || fail "shape $name --valence 5: exit $rc, expected 2"
done
[ ! -e "$work/x.obj" ] || fail "a usage error wrote x.obj"

if [ $failures -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "shape_assets: all checks passed"
