#!/usr/bin/env bash
# `pip wheel .` offline (pyproject.toml, setup.py): the wheel holds the package, the extension and
# the type stubs; it installs into a fresh venv (--system-site-packages: Debian's numpy) and
# imports from there, outside the source tree, where measure() of the globe is the CLI's report to
# the bit. The extension is built in ctest's own CMake build directory (POLARVIEW_CMAKE_BUILD_DIR:
# the target polarview_python, already up to date), so the test packs what the other tests test;
# a wheel from a clean clone configures its own (docs/python.md, "Install with pip").
# Args: <polarview executable> <repository root> <CMake build directory>
set -euo pipefail
exe=$1
root=$2
build=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
python=/usr/bin/python3
$python -m pip --version > /dev/null 2>&1 || fail "pip is missing (Debian: python3-pip; third_party/install_deps.sh)"

POLARVIEW_CMAKE_BUILD_DIR=$build $python -m pip wheel --no-build-isolation --no-deps --no-index -q "$root" -w "$tmp/dist" \
  > "$tmp/pip.log" 2>&1 || fail "pip wheel: $(tail -5 "$tmp/pip.log")"
wheel=$(ls "$tmp"/dist/polarview-*.whl)
$python - "$wheel" <<'PY' || fail "wheel contents"
import sys, zipfile
names = set(zipfile.ZipFile(sys.argv[1]).namelist())
need = {"polarview/__init__.py", "polarview/__init__.pyi", "polarview/_core.pyi", "polarview/py.typed"}
assert need <= names, need - names
assert [n for n in names if n.startswith("polarview/_core.") and n.endswith(".so")], names
metadata = zipfile.ZipFile(sys.argv[1]).read(next(n for n in names if n.endswith("METADATA"))).decode()
assert "Name: polarview" in metadata and "Requires-Dist: numpy" in metadata, metadata
assert "-cp3" in sys.argv[1] and "linux" in sys.argv[1], sys.argv[1]  # a platform wheel, not pure Python
PY

$python -m venv --system-site-packages "$tmp/venv"
"$tmp/venv/bin/python" -m pip install -q --no-index --no-deps "$wheel" > "$tmp/install.log" 2>&1 ||
  fail "pip install: $(tail -5 "$tmp/install.log")"
"$exe" measure "$root/assets/globe.obj" --scheme c2ps --level 2 --json > "$tmp/cli.json"
(cd "$tmp" && env -u PYTHONPATH "$tmp/venv/bin/python" - "$tmp" "$root/assets/globe.obj" "$tmp/cli.json") <<'PY' ||
import json, os, sys
import polarview
venv, globe, cli = sys.argv[1], sys.argv[2], sys.argv[3]
assert polarview.__file__.startswith(os.path.join(venv, "venv")), polarview.__file__
here = os.path.dirname(polarview.__file__)
assert {"__init__.pyi", "_core.pyi", "py.typed"} <= set(os.listdir(here)), os.listdir(here)
ours = polarview.measure(polarview.load(globe), "c2ps", 2)
theirs = json.load(open(cli))
for key in ("area", "volume", "closed"):
    assert ours[key] == theirs[key], (key, ours[key], theirs[key])
print("wheel: imported from", here)
PY
  fail "the installed wheel does not import or disagrees with the CLI"
echo "wheel: ok"
