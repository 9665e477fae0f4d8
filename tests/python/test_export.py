# tessellate(), export_surface() and ngon_to_fan() against the CLI's `export` and `convert`.
import numpy as np
import pytest

import polarview as pv
from conftest import MODELS, asset, cli_json, run_cli


def read_ply(path):
    """The CLI's binary PLY (formats.md): vertex x y z nx ny nz quality K H (double) r g b (uchar)."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    nv = int(header.split("element vertex ")[1].split()[0])
    nt = int(header.split("element face ")[1].split()[0])
    vertex = np.dtype([("p", "<f8", 3), ("n", "<f8", 3), ("q", "<f8"), ("K", "<f8"), ("H", "<f8"), ("c", "u1", 3)])
    face = np.dtype([("k", "u1"), ("i", "<i4", 3)])
    return np.frombuffer(data, vertex, nv, end), np.frombuffer(data, face, nt, end + nv * vertex.itemsize)


@pytest.mark.parametrize("model", MODELS)
def test_tessellate_is_the_ply_export_bit_for_bit(model, tmp_path):
    out = tmp_path / "surface.ply"
    run_cli("export", asset(model), "-o", out, "--scheme", "c2ps", "--level", 2, "--samples", 3)
    vertices, faces = read_ply(out)
    t = pv.tessellate(pv.load(asset(model)), "c2ps", 2, 3)
    assert np.array_equal(t["positions"], vertices["p"])
    assert np.array_equal(t["normals"], vertices["n"])
    assert np.array_equal(t["gaussian"], vertices["K"]) and np.array_equal(t["mean"], vertices["H"])
    assert np.array_equal(t["triangles"], faces["i"])
    assert np.array_equal(np.round(t["colours"] * 255.0), vertices["c"])
    assert t["watertight"] == (t["boundary_edges"] == 0)


def test_tessellate_checks_its_arguments():
    mesh = pv.load(asset("default"))
    with pytest.raises(ValueError, match="samples must be in 1..64"):
        pv.tessellate(mesh, samples=0)
    with pytest.raises(TypeError, match="uniform must be a bool"):
        pv.tessellate(mesh, uniform=1)
    with pytest.raises(ValueError, match="unknown scheme"):
        pv.tessellate(mesh, "loop")


def test_export_surface_writes_what_the_cli_writes(tmp_path):
    mesh = pv.load(asset("globe"))
    run_cli("export", asset("globe"), "-o", tmp_path / "cli.glb", "--scheme", "rts", "--level", 2, "--samples", 2)
    summary = pv.export_surface(mesh, tmp_path / "module.glb", "rts", 2, samples=2)
    assert "watertight" in summary
    assert (tmp_path / "module.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()
    with pytest.raises(ValueError, match="cannot tell the format"):
        pv.export_surface(mesh, tmp_path / "surface.xyz")
    with pytest.raises(ValueError, match="units must be one of"):
        pv.export_surface(mesh, tmp_path / "surface.step", units="furlong")
    assert not (tmp_path / "surface.step").exists()


def test_ngon_to_fan_makes_a_cylinders_caps_poles(tmp_path):
    # Blender's cylinder: two 8-gon caps, 8 quads between.
    n = 8
    angles = 2 * np.pi * np.arange(n) / n
    ring = np.c_[np.cos(angles), np.sin(angles)]
    vertices = np.r_[np.c_[ring, -np.ones(n)], np.c_[ring, np.ones(n)]]
    quads = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    indices = np.r_[np.ravel(quads), np.arange(n)[::-1], n + np.arange(n)]
    mesh = pv.Mesh(vertices, indices, [4] * n + [n, n])
    assert mesh.info()["poles"] == []
    fanned, centres = pv.ngon_to_fan(mesh)
    assert centres == [16, 17] and fanned.vertex_count == 18
    assert sorted(p["vertex"] for p in fanned.info()["poles"]) == centres
    mesh.save(tmp_path / "cylinder.obj")
    run_cli("convert", tmp_path / "cylinder.obj", "--ngon-to-fan", "-o", tmp_path / "fans.obj")
    cli = pv.load(tmp_path / "fans.obj")
    assert np.array_equal(cli.vertices, fanned.vertices)
    assert all(np.array_equal(a, b) for a, b in zip(cli.faces, fanned.faces))
    assert cli_json("info", tmp_path / "fans.obj", "--json")["poles"] == fanned.info()["poles"]
