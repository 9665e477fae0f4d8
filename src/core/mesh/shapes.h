// Parametric test and demo meshes with exact control over polar valence and ring count.
// All faces are counter-clockwise seen from outside; polar fans are (pole, q_{1j}, q_{1,j+1}).
#pragma once

#include <functional>
#include <string>

#include "core/mesh/poly_mesh.h"

namespace polarview::shapes {

// A surface of revolution z(t), rho(t), t in [0,1], from a top pole (t = 0) to a bottom pole
// (t = 1): `n` columns, `links` rings of quads' vertices strictly between the poles.
PolyMesh revolvePoles(int n, int links, const std::function<void(double t, double& rho, double& z)>& profile);

// UV sphere (globe): two n-valent poles and `links` latitude rings.
PolyMesh globe(int n, int links, double radius = 1.0);

// Open polar cap (like OpenSubdiv's catmark_pole shapes): an n-valent pole ringed by `links` links,
// the last one an open boundary; the surface is z = curvature/2 * r^2 over a disc.
PolyMesh polarCap(int n, int links, double radius = 1.0, double curvature = 1.0);
// The same layout over a height function z = height(x, y) (pole at the origin, links at radii
// radius * i / links).
PolyMesh heightCap(int n, int links, const std::function<double(double, double)>& height, double radius = 1.0);
// The height functions of the paper's test configurations (Figs. 4, 11, 13), by name: "paraboloid"
// (x^2 + y^2) / 2, "saddle" (x^2 - y^2) / 2, "monkey" x^3 - 3 x y^2, "flat4" (x^2 + y^2)^2 (a flat
// point), "saddle4" Re (x + i y)^4 (a 4th-order saddle), "convex" a dome steep at the rim (Fig. 4),
// "cone" -0.7 r, a sharp tip (Fig. 11);
// null for another name.
std::function<double(double, double)> paperHeight(const std::string& name);

// Mushroom: a polar cap (n-valent pole on top) over a stem whose bottom is closed by a k x k quad
// grid (n = 4k), which puts four valence-3 extraordinary vertices in a Catmull-Clark region.
PolyMesh mushroom(int n = 12);

// Closed unit cube of 6 quads (eight valence-3 extraordinary vertices).
PolyMesh cube();

// Blender's cylinder: an n-gon cap at each end (z = -1 and 1, radius 1), one ring of n quads between
// (bottom ring vertices 0..n-1, top n..2n-1). No polar configuration until the caps are triangle
// fans (core/mesh/ngon_to_fan.h).
PolyMesh ngonCylinder(int n);

// Torus as an nu x nv regular quad grid (every vertex 4-valent).
PolyMesh torus(int nu, int nv, double majorRadius = 1.0, double minorRadius = 0.35);

// Open planar-ish grid of nu x nv quads over [0,1]^2 with height z = height(x, y).
PolyMesh grid(int nu, int nv, const std::function<double(double, double)>& height = nullptr);

}  // namespace polarview::shapes
