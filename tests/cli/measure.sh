#!/usr/bin/env bash
# `polarview measure`: area, enclosed volume, centroids and inertia of the limit surface against
# OpenCASCADE's own integration of the exported STEP solid (sprops, vprops), to 1e-6 relative;
# the measures move as they must under a scale and a translation of the control mesh (area s^2,
# volume s^3, inertia s^5, centroids with the mesh) to 1e-9; an open surface has no volume.
# Usage: bash measure.sh <polarview-exe> <repo>
set -u
exe="$1"
repo="$2"
work=$(mktemp -d)
trap '[ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Against OpenCASCADE, reading the exported STEP as it comes (no sewing): the default model
# (moved off the origin, so centroid and inertia are not trivial), the globe and the CC cube, under
# C2PS 3 and CC 2, are each exactly one SOLID that checkshape passes and in which sewing finds no
# free and no multiple edge; its volume, centroid and inertia (vprops) and area, area centroid and
# shell inertia (sprops) equal measure's. An open cap reads as one shell whose free edges are one
# closed wire, its boundary.
python3 - "$repo/assets/default.obj" "$work/default_moved.obj" <<'PY'
import sys
out = open(sys.argv[2], "w")
for line in open(sys.argv[1]):
    if line.startswith("v "):
        x, y, z = (float(t) for t in line.split()[1:4])
        line = "v %r %r %r\n" % (x + 1.5, y - 0.5, z + 0.25)
    out.write(line)
PY
cases=()
for model in "$work/default_moved.obj" "$repo/assets/globe.obj" "$repo/assets/cube_cc2.obj"; do
  cases+=("$model c2ps 3" "$model cc 2")
done
: > "$work/occt.tcl"
for c in "${cases[@]}"; do
  set -- $c
  name=$(basename "$1" .obj)-$2-$3
  "$exe" measure "$1" --scheme "$2" --level "$3" --json > "$work/$name.json" || fail "measure $name"
  "$exe" export "$1" --scheme "$2" --level "$3" -o "$work/$name.step" > /dev/null || fail "export $name"
  cat >> "$work/occt.tcl" <<TCL
testreadstep $work/$name.step s
regexp {SOLID *: *([0-9]+)} [nbshapes s] all solids
regexp {SHELL *: *([0-9]+)} [nbshapes s] all shells
set valid [string match "*seems to be valid*" [checkshape s]]
puts "SHAPE $name \$solids \$shells \$valid"
sewing sw 1e-6 s
puts "VPROPS $name [string map {"\n" " "} [vprops s 1e-9 -full]]"
puts "SPROPS $name [string map {"\n" " "} [sprops s 1e-9 -full]]"
TCL
done
"$exe" export "$repo/assets/cap6_saddle.obj" --scheme rts --level 2 -o "$work/open.step" > /dev/null || fail "export open"
cat >> "$work/occt.tcl" <<TCL
testreadstep $work/open.step s
regexp {SOLID *: *([0-9]+)} [nbshapes s] all solids
regexp {SHELL *: *([0-9]+)} [nbshapes s] all shells
set valid [string match "*seems to be valid*" [checkshape s]]
puts "SEWING open"
sewing sw 1e-6 s
freebounds s 1e-6
regexp {WIRE *: *([0-9]+)} [nbshapes s_c] all closedwires
regexp {EDGE *: *([0-9]+)} [nbshapes s_c] all boundaryedges
regexp {WIRE *: *([0-9]+)} [nbshapes s_o] all openwires
puts "OPEN \$solids \$shells \$valid \$closedwires \$boundaryedges \$openwires"
TCL
if command -v occt-draw > /dev/null; then
  (cd "$work" && echo "pload ALL" | cat - occt.tcl > run.tcl && timeout 600 occt-draw -b -f run.tcl 2>&1) |
    grep -E '^(SHAPE|VPROPS|SPROPS|OPEN|SEWING) |Number of (Free|Multiple) Edges' > "$work/occt.txt"
  python3 - "$work" <<'PY' || fail "measure against OpenCASCADE"
import json, re, sys
work = sys.argv[1]
bad = []
def numbers(text, label):
    value = lambda key: float(re.search(key + r" *[:=] *([-0-9.e+]+)", text).group(1))
    matrix = [float(x) for x in re.search(r"Matrix of Inertia : *(([-0-9.e+]+ *){9})", text).group(1).split()]
    return value("Mass"), [value("X"), value("Y"), value("Z")], [matrix[0:3], matrix[3:6], matrix[6:9]]
def near(ours, theirs, scale, what):
    if abs(ours - theirs) > 1e-6 * scale:
        bad.append("%s: measure %.12g, OpenCASCADE %.12g" % (what, ours, theirs))
# Sewing prints its counts ("Number of Free Edges : n") after the SHAPE or SEWING line of its model.
rows, current = {}, None
for line in open(work + "/occt.txt"):
    counted = re.match(r" *Number of (Free|Multiple) Edges *: *([0-9]+)", line)
    if counted:
        rows[(counted.group(1), current)] = counted.group(2)
        continue
    tag, name, rest = (line.strip().split(" ", 2) + [""])[:3]
    rows[(tag, name)] = rest
    if tag in ("SHAPE", "SEWING"):
        current = name
names = sorted({n for t, n in rows if t == "SHAPE"})
if len(names) != 6:
    bad.append("OpenCASCADE read %d of the 6 models: %s" % (len(names), names))
for name in names:
    solids, shells, valid = rows[("SHAPE", name)].split()
    free, multiple = rows.get(("Free", name)), rows.get(("Multiple", name))
    if (solids, shells, valid, free, multiple) != ("1", "1", "1", "0", "0"):
        bad.append("%s: %s solid(s), %s shell(s), checkshape %s, sewing %s free and %s multiple edges"
                   % (name, solids, shells, "clean" if valid == "1" else "FAILS", free, multiple))
    m = json.load(open("%s/%s.json" % (work, name)))
    if not m["closed"]:
        bad.append(name + ": measure says open")
    size = max(abs(x) for x in m["centroid"]) + m["volume"] ** (1 / 3)
    for tag, mass, centroid, inertia in (("VPROPS", "volume", "centroid", "inertia"),
                                        ("SPROPS", "area", "area_centroid", "shell_inertia")):
        theirs = numbers(rows[(tag, name)], name)
        near(m[mass], theirs[0], abs(theirs[0]), "%s %s" % (name, mass))
        for i in range(3):
            near(m[centroid][i], theirs[1][i], size, "%s %s[%d]" % (name, centroid, i))
        largest = max(abs(x) for row in theirs[2] for x in row)
        for i in range(3):
            for j in range(3):
                near(m[inertia][i][j], theirs[2][i][j], largest, "%s %s[%d][%d]" % (name, inertia, i, j))
open_row = next((rest.split() for line in open(work + "/occt.txt") for tag, _, rest in [line.partition(" ")] if tag == "OPEN"), None)
if open_row is None:
    bad.append("the open cap: OpenCASCADE read nothing")
else:
    solids, shells, valid, closed_wires, boundary_edges, open_wires = open_row
    free = rows.get(("Free", "open"))
    if (solids, shells, valid, closed_wires, open_wires) != ("0", "1", "1", "1", "0") or free != boundary_edges or free == "0":
        bad.append("the open cap: %s solids, %s shells, checkshape %s, %s free edges, free bounds %s closed wire(s) of %s edges and %s open"
                   % (solids, shells, valid, free, closed_wires, boundary_edges, open_wires))
for b in bad:
    print("FAIL: " + b)
sys.exit(1 if bad else 0)
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
