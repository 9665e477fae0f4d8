// Area, enclosed volume, centroid and inertia of a limit surface, from its exact patches by
// Gauss-Legendre quadrature (`polarview measure`, the Python module's measure(), the viewer's Stats).
// The volume and the solid's moments come from the surface by the divergence theorem: for a closed
// surface with outward normals du x dv, V = 1/3 ∫ (x - o)·n dA and ∫_V f dV = ∫ F·n dA with div F = f.
// Each quantity's error is estimated as the difference from the same sum with half the points in
// each direction (the bicubic patches' volume integrand is a polynomial of degree 8 in each
// parameter: exact from 5 points; the area's is not polynomial). docs/commands.md (measure).
#pragma once

#include <glm/mat3x3.hpp>

#include <cstddef>
#include <vector>

#include "core/mesh/topology.h"
#include "core/spline/patch.h"

namespace polarview {

struct SurfaceMeasures {
  size_t patches = 0;
  int points = 0;                // Gauss-Legendre points per direction per patch
  bool closed = false;           // the solid's measures below are set only when closed
  double area = 0.0, areaError = 0.0;
  Point areaCentroid{0.0};       // of the surface as a shell of unit density per area
  glm::dmat3 shellInertia{0.0};  // the shell's inertia tensor about its centroid (unit density)
  double volume = 0.0, volumeError = 0.0;  // > 0 for outward normals (a counter-clockwise mesh)
  Point centroid{0.0};           // the solid's
  glm::dmat3 inertia{0.0};       // the solid's inertia tensor about its centroid (unit density)
};

// The measures of `patches` (a PatchSet's, or a view's) with `points` Gauss-Legendre points per
// direction (2..16) on each; `closed`: the surface bounds a solid (no boundary, no holes).
// [O(patches x points^2)]
SurfaceMeasures measureSurface(const std::vector<Patch>& patches, bool closed, int points = 8);

// Whether `mesh` bounds a solid: no boundary edge and no hole faces; `topology` is that of the mesh
// it is refined as (its manifold split where it has one: ModelAnalysis::topology). [O(edges)]
bool meshIsClosed(const PolyMesh& mesh, const MeshTopology& topology);
// The same, the tables built here. [O(mesh)]
bool meshIsClosed(const PolyMesh& mesh);

}  // namespace polarview
