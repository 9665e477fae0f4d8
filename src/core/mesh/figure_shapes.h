// The paper's figure inputs that are not height caps (Myles & Peters 2009, Figs. 2c and 12; the caps
// of Figs. 4, 11 and 13 are shapes::heightCap over shapes::paperHeight). The paper does not print
// its meshes: these are built to show what the figures show, not copies of them.
#pragma once

#include "core/mesh/poly_mesh.h"

namespace polarview::shapes {

// Fig. 12's "polar configuration of valence 20": a valence-20 pole ringed by 8 links over an
// elliptic bump z = 0.5 exp(-(x^2 / 0.5 + y^2 / 0.25)) on the unit disc, so that K is positive on
// top, negative on the flanks and near zero on the rim (the magnitude map's dark blue).
PolyMesh valence20Bump();

// Fig. 2c's "finger tips": a hand-like Catmull-Clark body (a box of 13 x 4 x 6 quads, palm of
// 3.25 x 0.8 x 2.4) with four fingers on top and a thumb on its side. Each finger is a tube of 8
// columns and 5 rings on a 2 x 2 block of the box's quads, closed by an 8-valent polar
// configuration; where a tube meets the box its block's corners become 5-valent extraordinary
// vertices of the Catmull-Clark region.
PolyMesh fingertips();

}  // namespace polarview::shapes
