"""C2PS polar subdivision surfaces (Myles & Peters 2009): meshes, refinement, limit patches, their
evaluation and the analysis of poles; numpy arrays in and out (docs/python.md).

The package is a thin layer over the extension ``polarview._core`` (src/python/*.cpp): it checks
the arguments' types and scheme names before they reach C++, so a wrong call raises a TypeError or
ValueError that names the argument. Value ranges (levels 0..64, rings 0..20, ...) are checked by the
extension, which raises ValueError; bad input files and meshes raise ValueError with the CLI's
one-line message, a level over the memory budget MemoryError.
"""
import numbers
import os

import numpy

from . import _core
from ._core import Mesh, Patches

__all__ = ["Mesh", "Patches", "SCHEMES", "POLAR_SCHEMES", "schemes", "scheme_name", "load", "shape", "refine",
           "limit_patches", "evaluate", "pole", "spectrum", "subdivision_matrix", "measure",
           "tessellate", "export_surface", "ngon_to_fan"]

# The scheme names in menu order and those with polar rules, from the C++ scheme table.
SCHEMES = tuple(row["name"] for row in _core.schemes())
POLAR_SCHEMES = tuple(row["name"] for row in _core.schemes() if row["polar"])


def schemes():
    """The schemes as the C++ table lists them: dicts with name, label, polar, uniform_first_step
    and min_valence (the least pole valence its polar rules refine; 0 for cc)."""
    return _core.schemes()


def scheme_name(name):
    """The command-line name of a scheme name: any case, and the aliases every command takes
    (``catmull-clark`` -> ``cc``, ``c2ps-uniform`` -> ``c2ps-u``). ValueError for unknown names."""
    return _core.scheme_name(_text("scheme", name))


def _text(argument, value):
    if not isinstance(value, str):
        raise TypeError(f"{argument} must be a str, not {type(value).__name__}")
    return value


def _scheme(value):
    if not isinstance(value, str):
        raise TypeError(f"scheme must be a str (one of {', '.join(SCHEMES)}), not {type(value).__name__}")
    return _core.scheme_name(value)


def _integer(argument, value, low=-(2**31), high=2**31 - 1):
    """An int argument (numpy integers too, not bool) within what the extension's C type holds."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{argument} must be an int, not {type(value).__name__}")
    value = int(value)
    if not low <= value <= high:
        raise ValueError(f"{argument} = {value} is out of range ({low}..{high})")
    return value


def _optional_integer(argument, value):
    return None if value is None else _integer(argument, value)


def _memory_budget(value):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"memory_budget must be an int (bytes; 0: 80% of the available memory), not {type(value).__name__}")
    if value < 0 or value >= 2**64:
        raise ValueError(f"memory_budget must be a number of bytes >= 0 (0: 80% of the available memory), got {value}")
    return int(value)


def _instance(argument, value, kind):
    if not isinstance(value, kind):
        raise TypeError(f"{argument} must be a polarview.{kind.__name__}, not {type(value).__name__}")
    return value


def load(path):
    """Reads an OBJ file (crease, corner and hole tags included) into a Mesh. ``path``: str or
    os.PathLike. The reader's warnings become UserWarnings; a malformed file raises ValueError with
    the CLI's message ``FILE:LINE: what``."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, not {type(path).__name__}")
    path = os.fspath(path)
    return _core.load(_text("path", path))


def shape(name, valence=None, links=None, height=""):
    """The meshes of ``polarview shape``: globe, cap, mushroom, cube, torus, valence20, fingertips;
    ``height`` names the cap's height function (paraboloid, saddle, monkey, flat4, saddle4, convex,
    cone). Unset sizes are the CLI's defaults (valence 12 in 3..2^20, links 6 in 1..2^16)."""
    return _core.shape(_text("name", name), _optional_integer("valence", valence), _optional_integer("links", links),
                       _text("height", height))


def refine(mesh, scheme="c2ps", levels=3, memory_budget=0):
    """The uniform control mesh after ``levels`` (0..64) steps of ``scheme``, point for point what
    ``polarview refine`` writes. ``memory_budget`` in bytes (0: 80% of the available memory); a level
    over it raises MemoryError."""
    return _core.refine(_instance("mesh", mesh, Mesh), _scheme(scheme), _integer("levels", levels),
                        _memory_budget(memory_budget))


def limit_patches(mesh, scheme="c2ps", level=3, uniform=False, memory_budget=0):
    """The limit surface's patches after ``level`` (0..64) levels, as ``polarview export`` makes them
    (feature-adaptive, or with ``uniform=True`` every face refined: the same patches)."""
    if not isinstance(uniform, (bool, numpy.bool_)):
        raise TypeError(f"uniform must be a bool, not {type(uniform).__name__}")
    return _core.limit_patches(_instance("mesh", mesh, Mesh), _scheme(scheme), _integer("level", level), bool(uniform),
                               _memory_budget(memory_budget))


def evaluate(patches, patch_ids, uv):
    """Position, normal, du, dv (Q, 3) and gaussian, mean, k1, k2 (Q,) at ``uv`` (Q, 2) in [0, 1]^2
    of the patches ``patch_ids`` (Q,) of ``patches`` (a Patches from limit_patches)."""
    return _core.evaluate(_instance("patches", patches, Patches), patch_ids, uv)


def pole(mesh, scheme="c2ps", rings=0):
    """Per refinable pole, what ``polarview pole --json --rings M`` prints: limit, normal, K, H,
    p0..p5 and with ``rings`` (0..20) > 0 the curvature over spline rings 1..M. ``scheme`` must be
    polar (one of POLAR_SCHEMES)."""
    return _core.pole(_instance("mesh", mesh, Mesh), _scheme(scheme), _integer("rings", rings))


def spectrum(scheme, valence, count=8, steps=8):
    """The leading ``count`` (>= 1) eigenvalues at ``valence`` (the scheme's least..64) with their
    eigenvectors and the matrix, as ``polarview spectrum --vectors``; c2ps: Lemma 5 measured over
    ``steps`` (1..12) steps, as ``polarview spectrum --scheme c2ps --json``."""
    return _core.spectrum(_scheme(scheme), _integer("valence", valence), _integer("count", count),
                          _integer("steps", steps))


def subdivision_matrix(mesh, scheme="c2ps"):
    """One refinement step as a scipy.sparse.csr_matrix: rows the new points (as refine(mesh,
    scheme, 1) lists them), columns the mesh's vertices."""
    return _core.subdivision_matrix(_instance("mesh", mesh, Mesh), _scheme(scheme))


def measure(mesh, scheme="c2ps", level=3, points=8, memory_budget=0):
    """Area, enclosed volume, centroid and inertia of the limit surface after ``level`` (0..64)
    levels, as ``polarview measure --json`` reports them: a dict with ``area``, ``area_error``,
    ``area_centroid`` (3,), ``shell_inertia`` (3, 3), ``closed`` and, for a closed surface,
    ``volume``, ``volume_error``, ``centroid`` (3,) and ``inertia`` (3, 3) about the centroid (unit
    density; None when open). ``points`` (2..16) Gauss-Legendre points per direction per patch."""
    return _core.measure(_instance("mesh", mesh, Mesh), _scheme(scheme), _integer("level", level),
                         _integer("points", points), _memory_budget(memory_budget))


def _flag(argument, value):
    if not isinstance(value, (bool, numpy.bool_)):
        raise TypeError(f"{argument} must be a bool, not {type(value).__name__}")
    return bool(value)


def tessellate(mesh, scheme="c2ps", level=3, samples=8, uniform=False, memory_budget=0):
    """The watertight triangle mesh ``polarview export OUT.ply --samples N`` writes, as a dict of
    arrays: ``positions``, ``normals`` (V, 3) float64 (exact unit normals), ``gaussian``, ``mean``
    (V,) (exact K and H), ``triangles`` (T, 3) uint32 (counter-clockwise seen from the normal),
    ``colours`` (V, 3) float32 (sRGB: K through the viewer's colour map over ``colour_range``, as
    the file's), ``patch`` (V,) and ``uv`` (V, 2) (where each vertex was evaluated), the edge counts
    ``boundary_edges``, ``non_manifold_edges``, ``misoriented_edges`` and ``watertight``.
    ``samples`` (1..64): segments along each patch edge."""
    return _core.tessellate(_instance("mesh", mesh, Mesh), _scheme(scheme), _integer("level", level),
                            _integer("samples", samples), _flag("uniform", uniform), _memory_budget(memory_budget))


def export_surface(mesh, path, scheme="c2ps", level=3, format=None, samples=8, units="mm", uniform=False,
                   memory_budget=0):
    """Writes the limit surface as ``polarview export`` does: bv, step, iges, ply or glb, from
    ``format`` or the path's extension; ``units`` (mm, m, inch) for STEP and IGES. The file is made
    atomically (nothing is left on an error). Returns the CLI's summary line."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, not {type(path).__name__}")
    return _core.export_surface(_instance("mesh", mesh, Mesh), os.fspath(path), _scheme(scheme),
                                _integer("level", level), "" if format is None else _text("format", format),
                                _integer("samples", samples), _text("units", units), _flag("uniform", uniform),
                                _memory_budget(memory_budget))


def ngon_to_fan(mesh, min_sides=5):
    """``polarview convert --ngon-to-fan``: every face of ``min_sides`` (>= 3) or more corners
    becomes a triangle fan around a new vertex at its centroid (a cylinder's n-gon caps become
    poles). Returns ``(mesh, centres)``: the new Mesh and the ids of the new centre vertices."""
    return _core.ngon_to_fan(_instance("mesh", mesh, Mesh), _integer("min_sides", min_sides))
