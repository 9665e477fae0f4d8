#!/usr/bin/env bash
# `polarview measure`: area and enclosed volume of the limit surface against OpenCASCADE's own
# integration of the exported STEP faces, sewn into one solid (sprops, vprops), to 1e-6 relative;
# the measures move as they must under a scale and a translation of the control mesh (area s^2,
# volume s^3, inertia s^5, centroids with the mesh) to 1e-9; an open surface has no volume.
# Usage: bash measure.sh <polarview-exe> <repo>
set -u
exe="$1"
repo="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Against OpenCASCADE: the globe (C2PS 3, poles and caps) and the CC cube (level 2).
cases=("globe c2ps 3" "cube_cc2 cc 2")
for c in "${cases[@]}"; do
  set -- $c
  "$exe" measure "$repo/assets/$1.obj" --scheme "$2" --level "$3" --json > "$work/$1.json" || fail "measure $1"
  "$exe" export "$repo/assets/$1.obj" --scheme "$2" --level "$3" -o "$work/$1.step" > /dev/null || fail "export $1"
  cat >> "$work/occt.tcl" <<TCL
testreadstep $work/$1.step s
sewing sw 1e-6 s
ssolid sw v
regexp {Mass : *([-0-9.e+]+)} [sprops s 1e-9 -full] all area
regexp {Mass : *([-0-9.e+]+)} [vprops v 1e-9 -full] all volume
puts "MEASURE $1 \$area \$volume"
TCL
done
if command -v occt-draw > /dev/null; then
  (cd "$work" && echo "pload ALL" | cat - occt.tcl > run.tcl && timeout 600 occt-draw -b -f run.tcl 2>&1) | grep '^MEASURE' > "$work/occt.txt"
  python3 - "$work" <<'PY' || fail "measure against OpenCASCADE: $(cat "$work/occt.txt")"
import json, sys
work = sys.argv[1]
rows = [line.split() for line in open(work + "/occt.txt")]
assert len(rows) == 2, rows
for _, name, area, volume in rows:
    m = json.load(open(f"{work}/{name}.json"))
    assert m["closed"], name
    for ours, theirs, what in ((m["area"], float(area), "area"), (m["volume"], float(volume), "volume")):
        assert abs(ours - theirs) <= 1e-6 * abs(theirs), (name, what, ours, theirs)
    assert m["volume_error"] < 1e-9 * m["volume"] and m["area_error"] < 1e-6 * m["area"], m
PY
else
  fail "occt-draw (OpenCASCADE's Draw) is not installed: third_party/install_deps.sh"
fi

# Scale by 2 and move by (10, -3, 5): every measure follows.
python3 - "$repo/assets/default.obj" "$work/moved.obj" <<'PY'
import sys
out = open(sys.argv[2], "w")
for line in open(sys.argv[1]):
    if line.startswith("v "):
        x, y, z = (float(t) for t in line.split()[1:4])
        line = "v %r %r %r\n" % (2 * x + 10, 2 * y - 3, 2 * z + 5)
    out.write(line)
PY
"$exe" measure "$repo/assets/default.obj" --scheme c2ps --level 3 --json > "$work/a.json" || fail "measure default"
"$exe" measure "$work/moved.obj" --scheme c2ps --level 3 --json > "$work/b.json" || fail "measure moved"
python3 - "$work/a.json" "$work/b.json" <<'PY' || fail "scale and translation"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
close = lambda x, y, scale: abs(x - y) <= 1e-9 * max(abs(y), scale)
assert close(b["area"], 4 * a["area"], 1) and close(b["volume"], 8 * a["volume"], 1), (a, b)
for key in ("centroid", "area_centroid"):
    for i, t in enumerate((10, -3, 5)):
        assert close(b[key][i], 2 * a[key][i] + t, 10), (key, a[key], b[key])
for key, power in (("inertia", 32), ("shell_inertia", 16)):
    for i in range(3):
        for j in range(3):
            assert close(b[key][i][j], power * a[key][i][j], power * a[key][0][0]), (key, a[key], b[key])
PY

# An open cap: the shell's measures, no volume.
"$exe" measure "$repo/assets/cap6_saddle.obj" --scheme rts --level 2 --json > "$work/open.json" || fail "measure open"
python3 -c "import json,sys; m=json.load(open(sys.argv[1])); assert not m['closed'] and m['volume'] is None and m['area'] > 0, m" \
  "$work/open.json" || fail "open surface: $(cat "$work/open.json")"

[ "$failures" -eq 0 ] || exit 1
echo "measure: ok"
