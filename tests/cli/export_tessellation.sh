#!/usr/bin/env bash
# `polarview export` to .ply and .glb: the Khronos glTF validator (npm, third_party/install_deps.sh)
# finds no error in the glb files; tests/cli/tessellation_readback.py reads the PLY with meshio and
# the glb with its own chunk parser and checks the summary's counts, watertightness (every edge twice,
# once each way), the Euler characteristic, the same mesh in both files, and K, H and the normal at
# the pole against `polarview pole --json`. Values past float's range are refused for glb with a
# one-line error, leaving no file and an existing one untouched.
# Args: <polarview executable> <repository root>.
set -euo pipefail
exe=$1
root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

validator="$root/third_party/node/node_modules/gltf-validator"
[ -f "$validator/package.json" ] || fail "no glTF validator at $validator: run third_party/install_deps.sh"
python=/usr/bin/python3

# name model scheme level samples euler boundary-loops [pole]
cases=(
  "default default.obj c2ps 3 4 2 0 pole"
  "cube cube_cc2.obj cc 3 4 2 0"
  "paraboloid cap12_paraboloid.obj c2ps 3 4 1 1 pole"
  "globe globe.obj bps 2 3 2 0"
)
glbs=()
for row in "${cases[@]}"; do
  read -r name model scheme level samples euler loops pole <<<"$row"
  for ext in ply glb; do
    "$exe" export "$root/assets/$model" -o "$tmp/$name.$ext" --scheme "$scheme" --level "$level" --samples "$samples" \
      >"$tmp/$name.$ext.txt"
    echo "$(cat "$tmp/$name.$ext.txt")"
  done
  summary=$(cat "$tmp/$name.ply.txt")
  [ "${summary#*: }" = "$(sed 's/^[^:]*: //' "$tmp/$name.glb.txt")" ] || fail "$name: ply and glb summaries differ"
  args=("$tmp/$name.ply" "$tmp/$name.glb" "$summary" "$euler" "$loops")
  if [ "${pole:-}" = pole ]; then
    "$exe" pole "$root/assets/$model" --scheme "$scheme" --json >"$tmp/$name.pole.json"
    args+=("$tmp/$name.pole.json")
  fi
  "$python" "$root/tests/cli/tessellation_readback.py" "${args[@]}" || fail "$name: read-back"
  glbs+=("$tmp/$name.glb")
done

# The Khronos validator: no errors (warnings and infos are printed).
/usr/bin/node - "$validator" "${glbs[@]}" <<'EOF' || fail "glTF validator"
const fs = require('fs');
const [validatorPath, ...files] = process.argv.slice(2);
const validator = require(validatorPath);
(async () => {
  let errors = 0;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)));
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
    for (const m of i.messages.slice(0, 5)) console.log(`  ${m.code}: ${m.message} (${m.pointer || ''})`);
    errors += i.numErrors;
  }
  process.exit(errors === 0 ? 0 : 1);
})();
EOF

# A model of 1e140: its glb positions would overflow float. Refused in one line naming the input,
# exit 1, nothing written, an existing file kept. (PLY holds doubles: it is written.)
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2*1e140, $3*1e140, $4*1e140; next} {print}' \
  "$root/assets/cap12_paraboloid.obj" >"$tmp/huge.obj"
echo old >"$tmp/huge.glb"
set +e
"$exe" export "$tmp/huge.obj" -o "$tmp/huge.glb" --scheme c2ps --level 2 >"$tmp/out.txt" 2>"$tmp/err.txt"
rc=$?
set -e
[ $rc -eq 1 ] || fail "huge.glb: exit $rc, expected 1"
[ "$(wc -l <"$tmp/err.txt")" -eq 1 ] || fail "huge.glb: not one line: $(cat "$tmp/err.txt")"
grep -q "huge.obj: the tessellation has a position past float's range" "$tmp/err.txt" || fail "huge.glb: $(cat "$tmp/err.txt")"
[ "$(cat "$tmp/huge.glb")" = old ] || fail "huge.glb: the existing file was replaced"
rm "$tmp/huge.glb"
"$exe" export "$tmp/huge.obj" -o "$tmp/huge.glb" --scheme c2ps --level 2 2>/dev/null && fail "huge.glb written"
[ -z "$(ls "$tmp" | grep -E '^huge\.glb')" ] || fail "a file was left: $(ls "$tmp")"
"$exe" export "$tmp/huge.obj" -o "$tmp/huge.ply" --scheme c2ps --level 2 >/dev/null || fail "huge.ply refused"
# A tessellation over the memory budget: refused before anything is allocated, naming the densest
# --samples that fits; that one is written.
set +e
"$exe" export "$root/assets/default.obj" -o "$tmp/dense.ply" --scheme c2ps --level 3 --samples 64 --memory-budget 20M \
  >"$tmp/out.txt" 2>"$tmp/err.txt"
rc=$?
set -e
[ $rc -eq 1 ] || fail "dense.ply: exit $rc, expected 1"
grep -q "default.obj: a tessellation of [0-9]* patches with --samples 64 needs about .* GB, over the memory budget" \
  "$tmp/err.txt" || fail "dense.ply: $(cat "$tmp/err.txt")"
[ ! -e "$tmp/dense.ply" ] || fail "dense.ply written"
fits=$(sed -n 's/.*(--samples \([0-9]*\) fits).*/\1/p' "$tmp/err.txt")
[ -n "$fits" ] && [ "$fits" -lt 64 ] || fail "dense.ply: no fitting --samples named: $(cat "$tmp/err.txt")"
"$exe" export "$root/assets/default.obj" -o "$tmp/dense.ply" --scheme c2ps --level 3 --samples "$fits" --memory-budget 20M \
  >/dev/null || fail "dense.ply: --samples $fits refused"
# A model of 1e-300: its curvature (1 / size^2) is past double's range: refused as render refuses it,
# nothing written (a STEP file, positions only, is written).
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2*1e-300, $3*1e-300, $4*1e-300; next} {print}' \
  "$root/assets/default.obj" >"$tmp/tiny.obj"
for ext in ply glb; do
  set +e
  "$exe" export "$tmp/tiny.obj" -o "$tmp/tiny.$ext" --scheme c2ps --level 1 >/dev/null 2>"$tmp/err.txt"
  rc=$?
  set -e
  [ $rc -eq 1 ] || fail "tiny.$ext: exit $rc, expected 1"
  grep -q "tiny.obj: the model spans .* below 1e-150" "$tmp/err.txt" || fail "tiny.$ext: $(cat "$tmp/err.txt")"
  [ ! -e "$tmp/tiny.$ext" ] || fail "tiny.$ext written"
done
"$exe" export "$tmp/tiny.obj" -o "$tmp/tiny.step" --scheme c2ps --level 1 >/dev/null || fail "tiny.step refused"
echo "export_tessellation: ok"
