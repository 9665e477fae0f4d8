# The analysis: pole() against `polarview pole --json`, spectrum() against the paper's Table 1 and
# `polarview spectrum`, subdivision_matrix() against refine()'s one step and Catmull-Clark's stencil.
import numpy as np
import pytest

import polarview as pv
from conftest import MODELS, asset, cli_json

POLAR_MODELS = ["default", "globe", "cap12_paraboloid", "cap6_saddle", "valence20", "fingertips"]


@pytest.mark.parametrize("name", POLAR_MODELS)
@pytest.mark.parametrize("scheme", ["c2ps", "rts", "bps", "c2ps-u"])
def test_pole_is_what_pole_json_prints(name, scheme):
    poles = pv.pole(pv.load(asset(name)), scheme, rings=3)
    assert poles == cli_json("pole", asset(name), "--scheme", scheme, "--rings", 3, "--json")["poles"]
    assert len(poles) >= 1


def test_pole_needs_a_polar_scheme():
    with pytest.raises(ValueError, match="polar scheme"):
        pv.pole(pv.load(asset("default")), "cc")


@pytest.mark.parametrize("n", [5, 8, 12, 32])
def test_rts_spectrum_is_table_1(n):
    s = pv.spectrum("rts", n, count=6)
    assert np.allclose(s["eigenvalues"], [1, 0.5, 0.5, 0.25, 0.25, 0.25], atol=1e-12)
    assert s["fourier_blocks"].tolist() == [0, 1, n - 1, 0, 2, n - 2]
    # Table 1's right eigenvectors v^_k, up to scale.
    table = [[1, 1, 1, 1, 1, 1], [0, 1, 2, 3, 4, 5], [0, 1, 2, 3, 4, 5], [-1, 2, 11, 26, 47, 74], [0, 2, 11, 26, 47, 74],
             [0, 2, 11, 26, 47, 74]]
    for profile, expected in zip(s["right_profile"], table):
        expected = np.array(expected, float)
        assert np.allclose(profile.real / profile.real[-1], expected / expected[-1], atol=1e-12)
    # The matrix (13) and its eigenvectors: A v = lambda v, w^T A = lambda w^T.
    a = s["matrix"]
    assert a.shape == (6 * n, 6 * n)
    for value, right, left in zip(s["eigenvalues"], s["right"], s["left"]):
        assert np.allclose(a @ right, value * right, atol=1e-12)
        assert np.allclose(left @ a, value * left, atol=1e-12)


@pytest.mark.parametrize("scheme,n", [("rts", 8), ("bps", 6), ("cc", 5)])
def test_spectrum_equals_polarview_spectrum(scheme, n):
    s = pv.spectrum(scheme, n, count=8)
    cli = cli_json("spectrum", "--scheme", scheme, "--valence", n, "--count", 8, "--vectors", "--json")
    assert s["size"] == cli["size"]
    for k, row in enumerate(cli["eigenvalues"]):
        assert s["eigenvalues"][k] == complex(row["re"], row["im"])
        assert s["modes"][k] == row["mode"]
        if row["right"] is not None:
            assert np.array_equal(s["right"][k].real, row["right"])
            assert np.array_equal(s["right_profile"][k].real, row["right_profile"])


def test_c2ps_spectrum_is_lemma_5_as_measured_by_the_cli():
    assert pv.spectrum("c2ps", 8, steps=4) == cli_json("spectrum", "--scheme", "c2ps", "--valence", 8, "--steps", 4, "--json")


@pytest.mark.parametrize("name", MODELS)
@pytest.mark.parametrize("scheme", ["cc", "c2ps", "c2ps-u", "rts", "bps"])
def test_subdivision_matrix_applied_to_the_points_is_one_refine_step(name, scheme):
    mesh = pv.load(asset(name))
    m = pv.subdivision_matrix(mesh, scheme)
    step = pv.refine(mesh, scheme, 1).vertices
    assert m.shape == (len(step), mesh.vertex_count) and m.format == "csr"
    size = np.abs(mesh.vertices).max()
    assert np.abs(m @ mesh.vertices - step).max() <= 1e-14 * size
    assert np.allclose(m.sum(axis=1), 1.0, atol=1e-14)  # affine invariance: every row sums to 1
    # Linear in each coordinate: the matrix maps any other points as the step does.
    other = np.random.default_rng(2).random(mesh.vertices.shape)
    moved = pv.refine(pv.Mesh(other, *mesh.faces), scheme, 1).vertices
    assert np.allclose(m @ other, moved, atol=1e-14)


def test_catmull_clark_rows_are_the_catmull_clark_stencils():
    torus = pv.shape("torus", valence=8, links=6)  # every vertex of valence 4
    m = pv.subdivision_matrix(torus, "cc").toarray()
    faces = torus.quads()
    f, v = len(faces), torus.vertex_count
    e = 2 * f  # a closed quad mesh: 2 edges a face
    assert m.shape == (f + e + v, v)
    for face in range(f):  # face points: the average of the corners
        assert np.array_equal(np.nonzero(m[face])[0], np.sort(faces[face])) and np.allclose(m[face][faces[face]], 0.25)
    for vertex in range(v):  # vertex points: 9/16 itself, 3/32 its 4 neighbours, 1/64 its 4 diagonals
        row = m[f + e + vertex]
        around = faces[(faces == vertex).any(axis=1)]
        neighbours = {int(q[(list(q).index(vertex) + s) % 4]) for q in around for s in (1, 3)}
        diagonals = {int(q[(list(q).index(vertex) + 2) % 4]) for q in around}
        assert row[vertex] == 9 / 16
        assert np.allclose(row[list(neighbours)], 3 / 32, rtol=0, atol=1e-16)
        assert np.allclose(row[list(diagonals)], 1 / 64, rtol=0, atol=1e-16)
        assert np.count_nonzero(row) == 9
