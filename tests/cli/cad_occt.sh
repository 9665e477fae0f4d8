#!/usr/bin/env bash
# STEP and IGES export judged by OpenCASCADE (occt-draw): every file reads, has one face per surface
# written and passes checkshape; OpenCASCADE's points, derivatives, K, H and area equal polarview's;
# seams are measured with OpenCASCADE's derivatives at the parameters `polarview continuity
# --samples 4` samples, and must agree with its JSON (tests/cad/occt_compare.py says what is checked).
# Then `polarview export`: the same files as the reference tool, the units named and read (OCCT
# scales inch and m files to its mm), coordinates unchanged, usage errors and a bad output path
# leave nothing behind.
# Args: <polarview executable> <repository root>; POLARVIEW_CAD_REFERENCE: tests/cad/cad_reference.
set -euo pipefail
exe=$1
root=$2
reference=${POLARVIEW_CAD_REFERENCE:-$(dirname "$exe")/tests/cad_reference}
compare="/usr/bin/python3 $root/tests/cad/occt_compare.py"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v occt-draw > /dev/null || fail "occt-draw (OpenCASCADE's Draw) is not installed: third_party/install_deps.sh"

"$exe" shape cap --valence 64 -o "$tmp/cap64.obj" > /dev/null

# MODEL SCHEME LEVEL [occt_compare options]: the reference files and OpenCASCADE's verdict, its
# seams against `polarview continuity`'s (the same K = 4 points a side).
judge() {
  local model=$1 scheme=$2 level=$3
  shift 3
  local name
  name=$(basename "$model" .obj)-$scheme-$level
  "$reference" "$model" "$scheme" "$level" "$tmp/$name" 4
  "$exe" continuity "$model" --scheme "$scheme" --level "$level" --samples 4 --json > "$tmp/$name.polarview.json"
  $compare "$tmp/$name" "$name" --continuity "$tmp/$name.continuity.json" --polarview "$tmp/$name.polarview.json" "$@" ||
    fail "$name: OpenCASCADE disagrees"
}
smooth=regular,ring-ring,regular-ring
judge "$root/assets/default.obj" c2ps 2 --g2 $smooth --not-g1 end-cap --t-junctions regular,ring-ring
judge "$root/assets/default.obj" rts 1 --g2 $smooth --not-g1 end-cap
judge "$root/assets/default.obj" bps 1 --g2 $smooth --not-g1 end-cap
judge "$root/assets/globe.obj" c2ps 1 --g2 ring-ring
judge "$tmp/cap64.obj" c2ps 1 --g2 $smooth
judge "$root/assets/cube_cc2.obj" cc 1 --g2 regular --not-g1 end-cap
# The rest of the four models x four schemes at level 1 (cube_cc2 has no pole: every scheme is
# Catmull-Clark there, the case above).
judge "$root/assets/default.obj" cc 1 --g2 regular --not-g1 end-cap
judge "$root/assets/globe.obj" rts 1 --g2 ring-ring
judge "$root/assets/globe.obj" bps 1 --g2 ring-ring
judge "$root/assets/globe.obj" cc 1 --g2 regular --not-g1 end-cap
judge "$tmp/cap64.obj" rts 1 --g2 $smooth
judge "$tmp/cap64.obj" bps 1 --g2 $smooth
judge "$tmp/cap64.obj" cc 1 --g2 regular --not-g1 end-cap
# Valence 5: each cap sector is written as 2 pieces, sampled at the sector's parameters, their
# seams counted per sector side (and the seam between a sector's pieces apart, as cap-piece).
"$exe" shape cap --valence 5 -o "$tmp/cap5.obj" > /dev/null
judge "$tmp/cap5.obj" c2ps 0 --g2 regular,ring-ring,regular-ring
[ "$(awk '$1 == "S" && $7 == 2' "$tmp/cap5-c2ps-0.table" | wc -l)" -eq 10 ] || fail "cap5: caps not in 2 pieces"
grep -q '"cap-piece"' "$tmp/cap5-c2ps-0.continuity.json" || fail "cap5: no seam between a sector's pieces"
# The agreement can fail: polarview's JSON with an end-cap angle 1e-5 off, a seam count one off, K = 8.
/usr/bin/python3 - "$tmp/cube_cc2-cc-1.polarview.json" "$tmp/tampered.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
end = next(s for s in d["seams"] if s["kind"] == "end-cap")
end["max_normal_angle"] *= 1 + 1e-5
end["count"] += 1
d["samples"] = 8
json.dump(d, open(sys.argv[2], "w"))
EOF
if $compare "$tmp/cube_cc2-cc-1" tampered --polarview "$tmp/tampered.json" > /dev/null 2> "$tmp/err"; then
  fail "occt_compare accepts a tampered polarview JSON"
fi
for what in "end-cap max_normal_angle" "end-cap count" "polarview sampled 8 points a side"; do
  grep -q "^FAIL: tampered: .*$what" "$tmp/err" || fail "tampered JSON, no '$what' failure: $(cat "$tmp/err")"
done

# `polarview export` writes what the reference tool wrote (the same rows; headers aside).
model="$root/assets/default.obj"
for ext in step igs; do
  line=$("$exe" export "$model" --scheme c2ps --level 2 -o "$tmp/cli.$ext")
  case "$line" in "$tmp/cli.$ext: 357 B-spline surfaces ("*"units mm; "*) ;; *) fail "summary: $line" ;; esac
done
diff <(sed -n '/^DATA;/,$p' "$tmp/cli.step") <(sed -n '/^DATA;/,$p' "$tmp/default-c2ps-2.step") > /dev/null ||
  fail "polarview export's STEP differs from the reference tool's"
diff <(grep -v '[SG] *[0-9]*$' "$tmp/cli.igs") <(grep -v '[SG] *[0-9]*$' "$tmp/default-c2ps-2.igs") > /dev/null ||
  fail "polarview export's IGES differs from the reference tool's"

# Units: named in the file, coordinates as they are; OpenCASCADE reads the unit (it scales to mm).
for unit in m inch; do
  for ext in step igs; do
    "$exe" export "$model" --scheme c2ps --level 1 --units $unit -o "$tmp/$unit.$ext" > /dev/null
  done
done
"$exe" export "$model" --scheme c2ps --level 1 -o "$tmp/mm.step" > /dev/null
"$exe" export "$model" --scheme c2ps --level 1 -o "$tmp/mm.igs" > /dev/null
grep -q "SI_UNIT(.MILLI.,.METRE.)" "$tmp/mm.step" || fail "mm STEP names no millimetre"
grep -q "LENGTH_UNIT()NAMED_UNIT(\*)SI_UNIT(\$,.METRE.)" "$tmp/m.step" || fail "m STEP names no metre"
grep -q "CONVERSION_BASED_UNIT('INCH',#[0-9]*)" "$tmp/inch.step" && grep -q "LENGTH_MEASURE(25.4)" "$tmp/inch.step" ||
  fail "inch STEP names no inch"
for unit in m inch; do
  points() { grep -o "CARTESIAN_POINT('',([^)]*))" "$1"; }  # without the entity numbers
  [ "$(points "$tmp/mm.step" | wc -l)" -gt 1000 ] || fail "mm STEP: too few points"
  diff <(points "$tmp/mm.step") <(points "$tmp/$unit.step") > /dev/null ||
    fail "$unit STEP: coordinates differ from the mm file's"
  diff <(grep 'P *[0-9]*$' "$tmp/mm.igs") <(grep 'P *[0-9]*$' "$tmp/$unit.igs") > /dev/null ||
    fail "$unit IGES: parameter data differ from the mm file's"
done
# IGES Global parameters 14 and 15 (units flag and name).
global_units() { /usr/bin/python3 -c "
import re, sys
text = ''.join(l[:72] for l in open(sys.argv[1]) if l[72:73] == 'G')
out, k = [], 0
while k < len(text) and len(out) < 15:
    m = re.match(r'(\d+)H', text[k:])
    if m: n = int(m.group(1)); s = text[k + len(m.group(0)):k + len(m.group(0)) + n]; k += len(m.group(0)) + n + 1
    else: e = min(i for i in (text.find(',', k), text.find(';', k)) if i >= 0); s = text[k:e]; k = e + 1
    out.append(s)
print(out[13], out[14])" "$1"; }
[ "$(global_units "$tmp/mm.igs")" = "2 MM" ] || fail "mm IGES units: $(global_units "$tmp/mm.igs")"
[ "$(global_units "$tmp/m.igs")" = "6 M" ] || fail "m IGES units: $(global_units "$tmp/m.igs")"
[ "$(global_units "$tmp/inch.igs")" = "1 INCH" ] || fail "inch IGES units: $(global_units "$tmp/inch.igs")"
cat > "$tmp/units.tcl" <<TCL
pload MODELING DATAEXCHANGE
foreach unit {mm m inch} {
  stepread $tmp/\$unit.step s *
  regexp {Mass : *([-0-9.e+]+)} [sprops s_1 1e-9 -full] all area
  puts "STEP \$unit \$area"
  igesread $tmp/\$unit.igs g *
  regexp {Mass : *([-0-9.e+]+)} [sprops g 1e-9 -full] all area
  puts "IGES \$unit \$area"
}
exit
TCL
occt-draw -b -f "$tmp/units.tcl" 2>&1 | grep -E '^(STEP|IGES) ' > "$tmp/units.txt"
/usr/bin/python3 - "$tmp/units.txt" <<'EOF' || fail "OpenCASCADE does not read the units"
import sys
area = {(w[0], w[1]): float(w[2]) for w in (l.split() for l in open(sys.argv[1]))}
for fmt in ("STEP", "IGES"):
    for unit, scale in (("m", 1000.0), ("inch", 25.4)):
        ratio = area[(fmt, unit)] / area[(fmt, "mm")]
        assert abs(ratio / scale ** 2 - 1) < 1e-9, (fmt, unit, ratio)
print("units: OpenCASCADE scales the m and inch files' areas by 1000^2 and 25.4^2 (STEP and IGES)")
EOF

# Usage errors and a bad output path: exit status, one line, nothing left behind.
set +e
"$exe" export "$model" --scheme c2ps --level 1 --units furlong -o "$tmp/furlong.step" 2> "$tmp/err"; rc=$?
set -e
[ $rc -eq 2 ] || fail "--units furlong: exit $rc, expected 2"
grep -q "units" "$tmp/err" || fail "--units furlong: $(cat "$tmp/err")"
[ ! -e "$tmp/furlong.step" ] || fail "--units furlong left a file"
mkdir "$tmp/out"
for ext in step igs; do
  set +e
  "$exe" export "$model" --scheme c2ps --level 1 -o "$tmp/out/missing/x.$ext" 2> "$tmp/err"; rc=$?
  set -e
  [ $rc -eq 1 ] || fail "a missing directory: exit $rc, expected 1"
  [ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "a missing directory: $(cat "$tmp/err")"
  [ -z "$(ls -A "$tmp/out")" ] || fail "a failed $ext export left $(ls -A "$tmp/out")"
done
echo "cad_occt: ok"
