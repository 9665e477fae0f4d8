#!/usr/bin/env bash
# Every data output of polarview, written into one folder, for a refactoring to compare before and
# after (`diff -r`): files the commands write, what they print (stdout; stderr with timings left out),
# the Python module's results, and PNGs of `render` and `figure`. Not a test: run it on two builds.
# Timings, memory and thread counts are not data (bench is left out; `render --time` too).
#   bash tests/support/output_snapshot.sh BUILD_DIR OUT_DIR      (needs Xvfb for the PNGs)
set -u
build="$(cd "$1" && pwd)"
out="$2"
pv="$build/polarview"
repo="$(cd "$(dirname "$0")/../.." && pwd)"
mkdir -p "$out"
cd "$out" || exit 1
a="$repo/assets"
# run NAME CMD...: stdout to NAME.out, the exit code to NAME.rc, stderr to NAME.err
run() {
  local name="$1"
  shift
  "$@" >"$name.out" 2>"$name.err"
  echo $? >"$name.rc"
}
for s in cc c2ps c2ps-u rts rts-u bps; do
  run "refine-$s" "$pv" refine "$a/default.obj" --scheme "$s" --levels 2 -o "refine-$s.obj"
  run "export-bv-$s" "$pv" export "$a/cap8_paraboloid.obj" --scheme "$s" --level 3 -o "export-$s.bv"
  run "export-step-$s" "$pv" export "$a/cap6_saddle.obj" --scheme "$s" --level 2 -o "export-$s.step"
  run "export-ply-$s" "$pv" export "$a/cap6_saddle.obj" --scheme "$s" --level 2 --samples 3 -o "export-$s.ply"
  run "continuity-$s" "$pv" continuity "$a/cap6_cone.obj" --scheme "$s" --level 2 --json
  run "continuity-text-$s" "$pv" continuity "$a/cap6_cone.obj" --scheme "$s" --level 2
done
run measure-globe "$pv" measure "$a/globe.obj" --scheme c2ps --level 3 --json
run measure-cap "$pv" measure "$a/cap6_saddle.obj" --scheme rts --level 2
run export-uniform "$pv" export "$a/cap8_paraboloid.obj" --scheme c2ps --level 2 --uniform -o export-uniform.bv
run export-iges "$pv" export "$a/globe.obj" --scheme rts --level 2 --units inch -o export.igs
run export-glb "$pv" export "$a/globe.obj" --scheme c2ps --level 2 --samples 4 -o export.glb
run export-format "$pv" export "$a/globe.obj" --scheme bps --level 1 --format bv -o export-format.txt
for f in default globe cube_cc2 fingertips valence20 cap12_monkey; do
  run "info-$f" "$pv" info "$a/$f.obj"
  run "info-json-$f" "$pv" info "$a/$f.obj" --json
done
for s in c2ps c2ps-u rts rts-u bps; do
  run "pole-$s" "$pv" pole "$a/cap12_saddle.obj" --scheme "$s" --rings 3
  run "pole-json-$s" "$pv" pole "$a/globe.obj" --scheme "$s" --json
done
run convert-ev "$pv" convert "$a/cube_cc2.obj" --ev-to-polar -o convert-ev.obj
run convert-ev5 "$pv" convert "$a/cube_cc2.obj" --ev-to-polar --pentagons -o convert-ev5.obj
run convert-fan "$pv" convert "$a/fingertips.obj" --ngon-to-fan -o convert-fan.obj
for shape in globe cap mushroom cube torus valence20 fingertips; do
  run "shape-$shape" "$pv" shape "$shape" -o "shape-$shape.obj"
done
run shape-cap-saddle "$pv" shape cap --valence 7 --links 4 --height saddle -o shape-cap-saddle.obj
for s in rts bps cc; do
  run "spectrum-$s" "$pv" spectrum --scheme "$s" --valence 6 --count 6
  run "spectrum-json-$s" "$pv" spectrum --scheme "$s" --valence 5 --vectors --json
done
run spectrum-c2ps "$pv" spectrum --scheme c2ps --valence 8
run spectrum-json-c2ps "$pv" spectrum --scheme c2ps --valence 6 --json
run help "$pv" help
run help-keys "$pv" help keys
for c in view render figure refine export continuity measure convert info pole bench shape spectrum; do
  run "help-$c" "$pv" "$c" --help
done
# Bad input: the one-line errors and exit codes.
printf 'v 0 0 0\nf 1 2 3\n' >bad.obj
run bad-index "$pv" info bad.obj
run bad-level "$pv" refine "$a/default.obj" --scheme c2ps --levels 30 -o never.obj
run bad-scheme "$pv" refine "$a/default.obj" --scheme catmull-clark --levels 1 -o never2.obj
# Pictures (software GL under Xvfb; same machine, same driver before and after).
xr=(xvfb-run -a -s "-screen 0 1600x900x24")
run render-k "${xr[@]}" "$pv" render "$a/default.obj" -o render-k.png --scheme c2ps,cc --level 3 --size 400x300
run render-h "${xr[@]}" "$pv" render "$a/globe.obj" -o render-h.png --scheme rts --level 4 --shade highlight --size 300x300 --net
run figure "${xr[@]}" "$pv" figure 12 -o figures --width 320
cp "$a/cap6_saddle.obj" viewed.obj  # the viewer's exports go beside the model
run view-do "${xr[@]}" "$pv" view viewed.obj --frames 2 --hidden --do level.3,edit.save
# The Python module: reports and arrays as text.
if [ -d "$build/python" ]; then
  PYTHONPATH="$build/python" /usr/bin/python3 - "$a" >python.out 2>python.err <<'EOF'
import sys, json, numpy as np, polarview as pv
a = sys.argv[1]
m = pv.load(a + "/default.obj")
print(json.dumps(m.info(), sort_keys=True))
for s in ["c2ps", "c2ps-u", "rts", "rts-u", "bps"]:
    print(json.dumps(pv.pole(pv.load(a + "/cap12_saddle.obj"), scheme=s, rings=2), sort_keys=True, default=str))
r = pv.refine(m, scheme="cc", levels=2)
print(r.vertex_count, r.face_count, np.asarray(r.vertices).sum())
p = pv.limit_patches(pv.load(a + "/cap8_paraboloid.obj"), scheme="c2ps", level=3)
print(len(p.kind), np.asarray(p.control_points).sum())
import hashlib
def digest(v):
    if isinstance(v, np.ndarray): return hashlib.sha256(np.ascontiguousarray(v).tobytes()).hexdigest()[:16] + str(v.shape)
    if isinstance(v, dict): return {k: digest(x) for k, x in sorted(v.items())}
    if isinstance(v, list): return [digest(x) for x in v]
    return v
for s in ["rts", "bps", "cc", "c2ps"]:
    print(s, digest(pv.spectrum(s, 6)))
EOF
  echo $? >python.rc
fi
# STEP and IGES name the time they were written; the memory budget follows the free memory.
sed -i -E "s/'[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:]{8}'/'TIME'/" *.step
sed -i -E 's/15H[0-9]{8}\.[0-9]{6}/15HTIME          /g' *.igs
sed -i -E 's/budget of [0-9.]+ GB/budget of N GB/' *.err
# Stderr carries timings in places: keep only lines that name no time.
for f in *.err; do grep -v -E '[0-9.]+ ?(ms|s)\b|seconds|MB/s|took' "$f" >"$f.kept"; mv "$f.kept" "$f"; done
echo "snapshot: $(ls | wc -l) files in $out"
