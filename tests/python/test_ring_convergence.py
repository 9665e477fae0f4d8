# examples/ring_convergence.py's claim (the paper's): on the default model C2PS's K converges to
# K(pole) ring by ring, RTS's stalls, and Catmull-Clark's has no limit at the valence-12 vertex.
import sys
from pathlib import Path

import numpy as np

import polarview as pv
from conftest import asset, cli_json

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples"))
import ring_convergence  # noqa: E402


def test_c2ps_converges_rts_stalls_catmull_clark_diverges():
    mesh = pv.load(asset("default"))
    c2ps, c2ps_pole = ring_convergence.polar_rings(mesh, "c2ps")
    rts, rts_pole = ring_convergence.polar_rings(mesh, "rts")
    assert np.isclose(c2ps_pole, rts_pole, rtol=1e-9)  # the same Taylor expansion (32) at the pole
    assert c2ps[-1] < 1e-3 and all(b < a for a, b in zip(c2ps, c2ps[1:]))
    assert min(rts[-3:]) > 0.09  # stalls near 0.1
    spreads, largest = ring_convergence.catmull_clark_rings(mesh)
    assert largest[-1] > 2 * largest[0] and spreads[-1] > spreads[0]
    # The rings' samples are the CLI's: pole --rings samples the same 5 x 5 grid of each patch.
    cli = cli_json("pole", asset("default"), "--scheme", "rts", "--rings", 8, "--json")["poles"][0]["rings"]
    assert np.allclose(rts, [ring["max_abs_dK"] for ring in cli], rtol=1e-9)
