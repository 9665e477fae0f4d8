# Type stubs of the package polarview (__init__.py); tests/python/test_package.py checks that every
# name, parameter and default here is the package's.
from os import PathLike
from typing import Any, Optional, Union

import numpy
import numpy.typing

from ._core import Mesh as Mesh, Patches as Patches

__all__: list[str]
SCHEMES: tuple[str, ...]
POLAR_SCHEMES: tuple[str, ...]

def schemes() -> list[dict[str, Any]]:
    """The schemes as the C++ table lists them: name, label, polar, uniform_first_step, min_valence."""
def scheme_name(name: str) -> str:
    """The command-line name of a scheme name (any case, aliases such as catmull-clark)."""
def load(path: Union[str, PathLike[str]]) -> Mesh:
    """Reads an OBJ file (crease, corner and hole tags included) into a Mesh."""
def shape(name: str, valence: Optional[int] = None, links: Optional[int] = None, height: str = "") -> Mesh:
    """The meshes of `polarview shape`: globe, cap, mushroom, cube, torus, valence20, fingertips."""
def refine(mesh: Mesh, scheme: str = "c2ps", levels: int = 3, memory_budget: int = 0) -> Mesh:
    """The uniform control mesh after `levels` steps of `scheme`, as `polarview refine` writes it."""
def limit_patches(mesh: Mesh, scheme: str = "c2ps", level: int = 3, uniform: bool = False,
                  memory_budget: int = 0) -> Patches:
    """The limit surface's patches after `level` levels, as `polarview export` makes them."""
def evaluate(patches: Patches, patch_ids: numpy.typing.ArrayLike, uv: numpy.typing.ArrayLike) -> dict[str, numpy.ndarray]:
    """position, normal, du, dv (Q, 3) and gaussian, mean, k1, k2 (Q,) at uv (Q, 2) of patch_ids (Q,)."""
def pole(mesh: Mesh, scheme: str = "c2ps", rings: int = 0) -> list[dict[str, Any]]:
    """Per refinable pole, what `polarview pole --json --rings M` prints."""
def spectrum(scheme: str, valence: int, count: int = 8, steps: int = 8) -> dict[str, Any]:
    """The leading eigenvalues and eigenvectors at `valence`, as `polarview spectrum --vectors`."""
def subdivision_matrix(mesh: Mesh, scheme: str = "c2ps") -> Any:
    """One refinement step as a scipy.sparse.csr_matrix."""
def measure(mesh: Mesh, scheme: str = "c2ps", level: int = 3, points: int = 8, memory_budget: int = 0) -> dict[str, Any]:
    """Area, enclosed volume, centroids and inertia, as `polarview measure --json` reports them."""
def tessellate(mesh: Mesh, scheme: str = "c2ps", level: int = 3, samples: int = 8, uniform: bool = False,
               memory_budget: int = 0) -> dict[str, Any]:
    """The watertight triangle mesh `polarview export OUT.ply --samples N` writes, as arrays."""
def export_surface(mesh: Mesh, path: Union[str, PathLike[str]], scheme: str = "c2ps", level: int = 3,
                   format: Optional[str] = None, samples: int = 8, units: str = "mm", uniform: bool = False,
                   memory_budget: int = 0) -> str:
    """Writes the limit surface as `polarview export` does (bv, step, iges, ply, glb); returns its summary."""
def ngon_to_fan(mesh: Mesh, min_sides: int = 5) -> tuple[Mesh, list[int]]:
    """`polarview convert --ngon-to-fan`: faces of min_sides or more corners become fans; (mesh, centres)."""
