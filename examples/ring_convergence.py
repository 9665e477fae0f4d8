#!/usr/bin/env python3
"""Curvature convergence towards the pole (docs/python.md): max |K - K(pole)| over spline ring m.

For C2PS and RTS the rings are the polar-ring patches of ring m around the pole of the default
model (assets/default.obj, a valence-12 pole) and K(pole) is the cap's curvature at the pole (the
Taylor expansion (32)). For Catmull-Clark, which treats the pole as an extraordinary vertex, ring m
is the ring of level-m regular patches around that vertex. Catmull-Clark's K has no limit there (at
valence 12 its subsubdominant eigenvalue exceeds the square of the subdominant one, so K grows
without bound towards the vertex): there is no K(pole), and its curve is the spread max K - min K
on ring m, which a surface with a K(pole) would drive to 0 as well (it is at most twice
max |K - K(pole)|). K is sampled on a 5 x 5 grid of every patch of a ring.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/ring_convergence.py [model.obj] [-o out.png]
"""
import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import polarview as pv  # noqa: E402

LEVELS = 8
GRID = np.array([(u, v) for u in np.linspace(0, 1, 5) for v in np.linspace(0, 1, 5)])


def curvature_on(patches, ids):
    """K at the GRID samples of each patch in ids (flattened)."""
    ids = np.repeat(ids, len(GRID))
    uv = np.tile(GRID, (len(ids) // len(GRID), 1))
    return pv.evaluate(patches, ids, uv)["gaussian"]


def polar_rings(mesh, scheme):
    """Per ring m = 1..LEVELS: max |K - K(pole)| on ring m of the first pole."""
    patches = pv.limit_patches(mesh, scheme, LEVELS)
    kind = pv.Patches.kind_names
    caps = np.nonzero((patches.kind == kind.index("pole-cap")) & (patches.pole == 0))[0]
    pole_k = pv.evaluate(patches, caps[:1], [[0.0, 0.0]])["gaussian"][0]
    rings = (patches.kind == kind.index("polar-ring")) & (patches.pole == 0)
    return [np.abs(curvature_on(patches, np.nonzero(rings & (patches.ring == m))[0]) - pole_k).max()
            for m in range(1, LEVELS + 1)], pole_k


def catmull_clark_rings(mesh):
    """Per level m = 1..LEVELS: max K - min K over the level-m regular patches around the pole
    vertex (those nearer to it than to any other extraordinary vertex)."""
    info = mesh.info()
    pole = info["poles"][0]["vertex"]
    others = [x["vertex"] for x in info["extraordinary_vertices"] if x["vertex"] != pole]
    patches = pv.limit_patches(mesh, "cc", LEVELS)
    centres = patches.control_points[:, 1:3, 1:3].mean(axis=(1, 2))
    near = np.linalg.norm(centres - mesh.vertices[pole], axis=1)
    for v in others:
        near_other = np.linalg.norm(centres - mesh.vertices[v], axis=1)
        near = np.where(near_other < near, np.inf, near)
    regular = (patches.kind == pv.Patches.kind_names.index("regular")) & np.isfinite(near)
    per_ring = [curvature_on(patches, np.nonzero(regular & (patches.level == m))[0]) for m in range(1, LEVELS + 1)]
    return [k.max() - k.min() for k in per_ring], [k.max() for k in per_ring]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", nargs="?", default=str(Path(__file__).resolve().parents[1] / "assets" / "default.obj"))
    parser.add_argument("-o", "--output", default="ring_convergence.png")
    args = parser.parse_args()
    mesh = pv.load(args.model)
    rings = range(1, LEVELS + 1)
    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=100)
    for label, scheme, style in [("C2PS", "c2ps", "o-"), ("RTS", "rts", "s-")]:
        errors, pole_k = polar_rings(mesh, scheme)
        ax.semilogy(rings, errors, style, label=f"{label}: max |K - K(pole)|, K(pole) = {pole_k:.4g}")
        print(f"{label:14s} K(pole) {pole_k:.6g}; max|K - K(pole)| on rings 1..{LEVELS}: " +
              " ".join(f"{e:.3g}" for e in errors))
    spreads, largest = catmull_clark_rings(mesh)
    ax.semilogy(rings, spreads, "^-", label="Catmull-Clark: max K - min K (no K(pole))")
    print(f"{'Catmull-Clark':14s} max K - min K on rings 1..{LEVELS}: " + " ".join(f"{e:.3g}" for e in spreads))
    print(f"{'':14s} max K on rings 1..{LEVELS}: " + " ".join(f"{e:.3g}" for e in largest))
    ax.set_xlabel("ring m (refinement level)")
    ax.set_ylabel("K on ring m: distance from K(pole), or spread")
    ax.set_title(f"Curvature towards the pole: {Path(args.model).name}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
