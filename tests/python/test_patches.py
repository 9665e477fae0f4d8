# Limit patches: the control points against an independent B-spline and Bezier evaluation, the
# patches of every kind against evaluate(), and the curvature at a paraboloid cap's pole.
import numpy as np
import pytest

import polarview as pv
from conftest import asset, cli_json


def bspline_basis(t):
    """Uniform cubic B-spline basis and its derivative on the middle knot span (docs/patches.md)."""
    value = np.array([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3]) / 6
    slope = np.array([-3 * (1 - t) ** 2, 9 * t**2 - 12 * t, -9 * t**2 + 6 * t + 3, 3 * t**2]) / 6
    return value, slope


def bernstein(t):
    return np.array([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t**2 * (1 - t), t**3])


@pytest.fixture(scope="module")
def default_patches():
    return pv.limit_patches(pv.load(asset("default")), "c2ps", 3)


def test_arrays_are_views_with_the_documented_shapes(default_patches):
    p = default_patches
    count = len(p)
    assert p.control_points.shape == (count, 4, 4, 3) and p.control_points.dtype == np.float64
    assert p.kind.shape == p.level.shape == p.ring.shape == p.pole.shape == p.face.shape == (count,)
    assert not p.control_points.flags.writeable and not p.control_points.flags.owndata
    assert sum(p.counts().values()) == count
    kinds = [pv.Patches.kind_names[k] for k in p.kind]
    assert {name: kinds.count(name) for name in pv.Patches.kind_names} == p.counts()
    caps = p.kind == pv.Patches.kind_names.index("pole-cap")
    assert (p.face[caps] == -1).all() and (p.ring[caps] == 3).all() and (p.pole[caps] == 0).all()
    assert caps.sum() == 96  # C2PS at level 3 on the valence-12 pole: 12 * 2^3 sectors


def test_bspline_control_points_and_bezier_points_evaluate_to_the_surface(default_patches):
    p = default_patches
    rng = np.random.default_rng(1)
    ids = np.nonzero(p.kind != pv.Patches.kind_names.index("pole-cap"))[0]
    uv = rng.random((len(ids), 2))
    surface = pv.evaluate(p, ids, uv)
    cp, bezier = p.control_points[ids], p.bezier()[ids]
    for q in range(len(ids)):
        (bu, du), (bv, dv) = bspline_basis(uv[q, 0]), bspline_basis(uv[q, 1])
        # [p, j, i]: i along u, j along v (patch.h)
        assert np.allclose(np.einsum("j,i,jic->c", bv, bu, cp[q]), surface["position"][q], atol=1e-13)
        assert np.allclose(np.einsum("j,i,jic->c", bv, du, cp[q]), surface["du"][q], atol=1e-12)
        assert np.allclose(np.einsum("j,i,jic->c", dv, bu, cp[q]), surface["dv"][q], atol=1e-12)
        bez = np.einsum("j,i,jic->c", bernstein(uv[q, 1]), bernstein(uv[q, 0]), bezier[q])
        assert np.allclose(bez, surface["position"][q], atol=1e-13)
    normal = np.cross(surface["du"], surface["dv"])
    assert np.allclose(normal / np.linalg.norm(normal, axis=1)[:, None], surface["normal"], atol=1e-12)
    k = surface
    assert np.allclose(k["k1"] * k["k2"], k["gaussian"], atol=1e-9) and np.allclose((k["k1"] + k["k2"]) / 2, k["mean"])


@pytest.mark.parametrize("source", ["asset", "shape"])
@pytest.mark.parametrize("scheme", ["c2ps", "c2ps-u", "rts"])
def test_paraboloid_cap_has_K_4a2_at_the_pole(source, scheme):
    # z = a (x^2 + y^2), a = 1/2 (assets/README.md): K = 4 a^2 = 1 and H = 2 a = 1 at the pole.
    mesh = pv.load(asset("cap12_paraboloid")) if source == "asset" else pv.shape("cap", valence=12, height="paraboloid")
    p = pv.limit_patches(mesh, scheme, 3)
    caps = np.nonzero(p.kind == pv.Patches.kind_names.index("pole-cap"))[0]
    at_pole = pv.evaluate(p, caps, np.column_stack([np.zeros(len(caps)), np.linspace(0, 1, len(caps))]))
    a = 0.5
    assert np.allclose(at_pole["gaussian"], 4 * a * a, atol=1e-12)
    assert np.allclose(at_pole["mean"], 2 * a, atol=1e-12)
    assert np.allclose(at_pole["position"], at_pole["position"][0], atol=1e-15)
    assert np.allclose(at_pole["normal"][:, 2], 1.0)
    assert np.isclose(pv.pole(mesh, scheme)[0]["gaussian_curvature"], 4 * a * a, atol=1e-12)


def test_evaluate_checks_its_arguments(default_patches):
    with pytest.raises(ValueError, match="out of range"):
        pv.evaluate(default_patches, [len(default_patches)], [[0.5, 0.5]])
    with pytest.raises(ValueError, match=r"outside \[0, 1\]"):
        pv.evaluate(default_patches, [0], [[0.5, 1.5]])
    with pytest.raises(ValueError, match=r"\(Q, 2\)"):
        pv.evaluate(default_patches, [0, 1], [[0.5, 0.5]])
