#!/usr/bin/env bash
# `polarview view --do CMD,...` runs the viewer's commands ("level 7" or "level.7", "camera.frame";
# the same table as its keys, buttons and help: src/session/command_table.cpp) once the model is
# loaded; `polarview help keys` lists them.
# Usage: bash viewer_do.sh <polarview-exe> <repo>. Needs X: re-runs under Xvfb.
set -u
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
repo="$2"
. "$repo/tests/support/gl_script.sh" "$@"  # Xvfb when needed; $work, fail, $failures

"$exe" help keys > "$work/keys.txt" || fail "help keys exited with $?"
grep -Eq '^  shade\.gaussian +G ' "$work/keys.txt" || fail "help keys does not list shade.gaussian with G: $(head -3 "$work/keys.txt")"
grep -Eq '^  edit\.redo +Ctrl\+Shift\+Z / Ctrl\+Y ' "$work/keys.txt" || fail "help keys: edit.redo's keys"

# The commands as keys would run them: G, V, 2, then S on the active (first) view: CC -> C2PS-U.
(cd "$work" && "$exe" view --do shade.gaussian,views.cycle,level.2 --do scheme.next --frames 1 --stats --hidden \
  --size 800x500) > "$work/stats.json" 2> "$work/err.txt" || fail "view --do exited with $?: $(cat "$work/err.txt")"
python3 - "$work/stats.json" <<'PY' || fail "view --do stats: $(cat "$work/stats.json")"
import json, sys
d = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
assert d["views"] == 2 and d["shade"] == "gaussian" and d["level"] == 2, d
assert d["schemes"] == ["c2ps-u", "rts"], d["schemes"]
PY

# Commands with an argument after a space, as the dotted ids read (level 2 = level.2, shade mean =
# shade.mean); the last shading asked for wins.
(cd "$work" && "$exe" view --do "level 2,shade mean,views.cycle" --do shade.gaussian --frames 1 --stats --hidden \
  --size 800x500) > "$work/stats2.json" 2> "$work/err.txt" || fail "view --do 'level 2,...' exited with $?: $(cat "$work/err.txt")"
python3 - "$work/stats2.json" <<'PY' || fail "view --do with arguments: $(cat "$work/stats2.json")"
import json, sys
d = json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])
assert d["views"] == 2 and d["shade"] == "gaussian" and d["level"] == 2, d
PY
grep -Eq '^  level N +0 - 9 ' "$work/keys.txt" || fail "help keys does not list level N with 0 - 9"

# edit.save in the first frame, nothing moved: the model file again, byte for byte (vt, vn, o, s,
# mtllib, usemtl, f v/vt/vn and the 6-decimal numbers kept), as <model>_edited.obj beside it.
printf '# Blender 3.6.5\nmtllib box.mtl\no Box\nv 1.000000 1.000000 -1.000000\nv 1.000000 -1.000000 -1.000000\nv 1.000000 1.000000 1.000000\nv 1.000000 -1.000000 1.000000\nv -1.000000 1.000000 -1.000000\nv -1.000000 -1.000000 -1.000000\nv -1.000000 1.000000 1.000000\nv -1.000000 -1.000000 1.000000\nvn -0.0000 1.0000 -0.0000\nvt 0.625000 0.500000\ns 0\nusemtl Material\nf 1/1/1 5/1/1 7/1/1 3/1/1\nf 4/1/1 3/1/1 7/1/1 8/1/1\nf 8/1/1 7/1/1 5/1/1 6/1/1\nf 6/1/1 2/1/1 4/1/1 8/1/1\nf 2/1/1 1/1/1 3/1/1 4/1/1\nf 6/1/1 5/1/1 1/1/1 2/1/1\n' > "$work/box.obj"
"$exe" view "$work/box.obj" --do edit.save --frames 1 --hidden --size 800x500 > /dev/null 2> "$work/err.txt" ||
  fail "view --do edit.save exited with $?: $(cat "$work/err.txt")"
cmp -s "$work/box.obj" "$work/box_edited.obj" || fail "edit.save of an unedited file changed it: $(diff "$work/box.obj" "$work/box_edited.obj" | head -5)"

"$exe" view --do shade.gaussian,no.such.command --frames 1 --hidden > /dev/null 2> "$work/usage.txt"
[ $? -eq 2 ] || fail "an unknown --do command is not a usage error"
grep -q "unknown viewer command 'no.such.command'" "$work/usage.txt" || fail "no message: $(cat "$work/usage.txt")"

# A bad argument: a usage error whose one line says what is accepted.
for bad in "level 25:level N: N is 0..24, not '25'" "shade.foo:shade MODE: MODE is shaded|gaussian|mean|highlight|reflection, not 'foo'"; do
  "$exe" view --do "${bad%%:*}" --frames 1 --hidden > /dev/null 2> "$work/usage.txt"
  [ $? -eq 2 ] || fail "--do '${bad%%:*}' is not a usage error"
  grep -qF -- "--do: ${bad#*:}" "$work/usage.txt" || fail "--do '${bad%%:*}': $(head -1 "$work/usage.txt")"
done

[ "$failures" -eq 0 ] || exit 1
echo "viewer_do: ok"
