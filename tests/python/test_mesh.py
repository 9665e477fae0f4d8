# Meshes: load and Mesh(V, F) against an independent OBJ reader, info() and refine() and shape()
# against the CLI, and the errors the CLI prints raised as ValueError / MemoryError.
import numpy as np
import pytest

import polarview as pv
from conftest import MODELS, asset, cli_json, faces_of, read_obj, run_cli


@pytest.mark.parametrize("name", MODELS)
def test_load_reads_the_obj_exactly(name):
    mesh = pv.load(asset(name))
    vertices, faces = read_obj(asset(name))
    assert mesh.vertices.dtype == np.float64 and mesh.vertices.shape == vertices.shape
    assert np.array_equal(mesh.vertices, vertices)
    assert faces_of(mesh) == faces
    assert not mesh.vertices.flags.writeable and not mesh.vertices.flags.owndata  # a view


def test_mesh_from_arrays_equals_the_loaded_mesh_in_both_face_forms():
    loaded = pv.load(asset("cube_cc2"))
    quads = loaded.quads()
    assert quads.shape == (loaded.face_count, 4)
    square = pv.Mesh(loaded.vertices, quads)
    indices, sizes = loaded.faces
    flat = pv.Mesh(loaded.vertices.tolist(), indices.tolist(), sizes)
    for mesh in (square, flat):
        assert np.array_equal(mesh.vertices, loaded.vertices)
        assert faces_of(mesh) == faces_of(loaded)
    single = loaded.vertices.astype(np.float32)
    assert np.array_equal(pv.Mesh(single, quads).vertices, single.astype(np.float64))
    # The same mesh refines to the same points.
    assert np.array_equal(pv.refine(square, "cc", 2).vertices, pv.refine(loaded, "cc", 2).vertices)


def test_crease_tags_are_read(tmp_path):
    obj = tmp_path / "creased.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt crease 2/1/0 0 1 2.5\nt corner 1/1/0 2 10\n")
    with pytest.warns(UserWarning, match="1 crease edges and 1 corners"):
        tags = pv.load(str(obj)).tags
    assert tags["crease_edges"].tolist() == [[0, 1]] and tags["crease_sharpness"].tolist() == [2.5]
    assert tags["corners"].tolist() == [2] and tags["corner_sharpness"].tolist() == [10.0]


@pytest.mark.parametrize("name", MODELS)
def test_info_is_what_info_json_prints(name):
    assert pv.load(asset(name)).info() == cli_json("info", asset(name), "--json")


@pytest.mark.parametrize("name,scheme,levels", [("default", "c2ps", 3), ("default", "rts", 2), ("globe", "bps", 2),
                                                ("globe", "rts-u", 2), ("cube_cc2", "cc", 2), ("fingertips", "c2ps", 1)])
def test_refine_equals_polarview_refine(tmp_path, name, scheme, levels):
    out = tmp_path / "refined.obj"
    run_cli("refine", asset(name), "-o", out, "--scheme", scheme, "--levels", levels)
    vertices, faces = read_obj(out)
    refined = pv.refine(pv.load(asset(name)), scheme=scheme, levels=levels)
    assert np.array_equal(refined.vertices, vertices)  # shortest decimals read back to the same doubles
    assert faces_of(refined) == faces


@pytest.mark.parametrize("args", [("cap", {"valence": 12, "height": "saddle"}), ("globe", {"valence": 8, "links": 4}),
                                  ("valence20", {}), ("mushroom", {})])
def test_shape_equals_polarview_shape(tmp_path, args):
    name, options = args
    out = tmp_path / "shape.obj"
    flags = [x for key, value in options.items() for x in (f"--{key}", value)]
    run_cli("shape", name, *flags, "-o", out)
    vertices, faces = read_obj(out)
    mesh = pv.shape(name, **options)
    assert np.array_equal(mesh.vertices, vertices) and faces_of(mesh) == faces


def cli_error(*args):
    code, _, stderr = run_cli(*args, check=False)
    assert code != 0 and stderr.startswith("polarview: ")
    return stderr.splitlines()[0][len("polarview: "):]


def test_bad_input_raises_value_error_with_the_cli_message(tmp_path):
    malformed = tmp_path / "malformed.obj"
    malformed.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    nan_vertex = tmp_path / "nan.obj"
    nan_vertex.write_text("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")
    for path in (malformed, nan_vertex, tmp_path / "missing.obj"):
        with pytest.raises(ValueError) as error:
            pv.load(str(path))
        assert str(error.value) == cli_error("info", path)
        assert str(error.value).startswith(str(path) + ":")
    assert ":4: face index 7 out of range" in cli_error("info", malformed)
    assert ":2: " in cli_error("info", nan_vertex) and "NaN" in cli_error("info", nan_vertex)


def test_array_input_is_checked():
    good = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    for vertices, faces in [(np.array([[0.0, 0, 0], [np.inf, 0, 0], [0, 1, 0]]), [[0, 1, 2]]),
                            (good, [[0, 1, 3]]), (good, [[0, 1]]), (good[:, :2], [[0, 1, 2]])]:
        with pytest.raises(ValueError, match="^<arrays>: "):
            pv.Mesh(vertices, np.array(faces))
    with pytest.raises(ValueError, match="not every face is a quad"):
        pv.load(asset("default")).quads()


def test_a_level_over_the_memory_budget_raises_memory_error_with_the_cli_message(tmp_path):
    mesh = pv.load(asset("default"))
    with pytest.raises(MemoryError) as error:
        pv.refine(mesh, "c2ps", 6, memory_budget=1 << 20)
    assert str(error.value) == cli_error("refine", asset("default"), "-o", tmp_path / "x.obj", "--levels", 6,
                                         "--memory-budget", "1M")
    assert not (tmp_path / "x.obj").exists()
    with pytest.raises(MemoryError, match="over the memory budget"):
        pv.limit_patches(mesh, "c2ps", 40)  # the default budget: 80% of the available memory


def test_unknown_names_raise_value_error():
    with pytest.raises(ValueError, match="unknown scheme 'c3ps'"):
        pv.refine(pv.load(asset("default")), "c3ps", 1)
    with pytest.raises(ValueError, match="unknown shape 'blob'"):
        pv.shape("blob")
    with pytest.raises(ValueError, match="do not apply to valence20"):
        pv.shape("valence20", valence=8)


def _cube_with_tags(tmp_path):
    """A cube as arrays and as an OBJ with the same `t crease` / `t corner` tags (later ones override)."""
    V = np.array([[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)], float)
    F = np.array([[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [1, 3, 7, 5], [3, 2, 6, 7], [2, 0, 4, 6]])
    edges, sharpness = [[0, 1], [1, 3], [3, 2], [2, 0], [1, 0]], [2.5, 10, 10, 0.5, 3.0]
    path = tmp_path / "tagged.obj"
    with open(path, "w") as f:
        f.writelines("v %r %r %r\n" % tuple(v) for v in V)
        f.writelines("f " + " ".join(str(i + 1) for i in face) + "\n" for face in F)
        f.writelines("t crease 2/1/0 %d %d %r\n" % (a, b, s) for (a, b), s in zip(edges, sharpness))
        f.write("t corner 1/1/0 7 1.5\n")
    return V, F, edges, sharpness, path


def test_crease_and_corner_arrays_are_the_obj_tags(tmp_path):
    V, F, edges, sharpness, path = _cube_with_tags(tmp_path)
    ours = pv.Mesh(V, F, crease_edges=edges, crease_sharpness=sharpness, corners=[7], corner_sharpness=[1.5])
    with pytest.warns(UserWarning):
        theirs = pv.load(path)
    for key in ("crease_edges", "crease_sharpness", "corners", "corner_sharpness"):
        np.testing.assert_array_equal(ours.tags[key], theirs.tags[key])
    assert ours.tags["crease_sharpness"].tolist() == [3.0, 0.5, 10.0, 10.0]  # (0, 1): the later 3.0
    a, b = pv.limit_patches(ours, "cc", 3), pv.limit_patches(theirs, "cc", 3)
    np.testing.assert_array_equal(a.control_points, b.control_points)
    plain = pv.limit_patches(pv.Mesh(V, F), "cc", 3)
    assert plain.control_points.shape != a.control_points.shape or not np.allclose(plain.control_points, a.control_points)


@pytest.mark.parametrize("tags, message", [
    (dict(crease_edges=[[0, 7]], crease_sharpness=[1.0]), "not an edge of any face"),
    (dict(crease_edges=[[0, 99]], crease_sharpness=[1.0]), "out of range"),
    (dict(crease_edges=[[0, 1]], crease_sharpness=[float("nan")]), "finite"),
    (dict(crease_edges=[[0, 1]], crease_sharpness=[-1.0]), "finite and >= 0"),
    (dict(crease_edges=[[0, 1]]), "go together"),
    (dict(crease_edges=[0, 1], crease_sharpness=[1.0]), "(E, 2)"),
    (dict(corners=[8], corner_sharpness=[1.0]), "out of range"),
])
def test_bad_crease_and_corner_arrays_are_refused(tmp_path, tags, message):
    V, F, *_ = _cube_with_tags(tmp_path)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        pv.Mesh(V, F, **tags)
