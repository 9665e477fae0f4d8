# The Python module's tests (docs/python.md): run by ctest as python.pytest, with PYTHONPATH at
# build/python and POLARVIEW_BIN the CLI the results are compared with.
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ASSETS = Path(__file__).resolve().parents[2] / "assets"
# The shipped models the comparisons loop over (assets/README.md says what each is).
MODELS = ["default", "globe", "cube_cc2", "convex16", "cap12_paraboloid", "cap6_saddle", "valence20", "fingertips"]


def asset(name):
    return str(ASSETS / f"{name}.obj")


def cli_binary():
    path = os.environ.get("POLARVIEW_BIN")
    if not path:
        pytest.skip("POLARVIEW_BIN not set (ctest sets it to the built polarview)")
    return path


def run_cli(*args, check=True):
    """Runs the polarview CLI; returns (exit code, stdout, stderr)."""
    done = subprocess.run([cli_binary(), *map(str, args)], capture_output=True, text=True, timeout=60)
    if check and done.returncode != 0:
        raise AssertionError(f"polarview {' '.join(map(str, args))} failed: {done.stderr}")
    return done.returncode, done.stdout, done.stderr


def cli_json(*args):
    return json.loads(run_cli(*args)[1])


def read_obj(path):
    """An independent reader of the OBJ files the CLI writes: v lines and 1-based f lines."""
    vertices, faces = [], []
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if words and words[0] == "v":
            vertices.append([float(x) for x in words[1:4]])
        elif words and words[0] == "f":
            faces.append([int(w.split("/")[0]) - 1 for w in words[1:]])
    return np.array(vertices), faces


def faces_of(mesh):
    indices, sizes = mesh.faces
    return [list(face) for face in np.split(indices, np.cumsum(sizes)[:-1])]
