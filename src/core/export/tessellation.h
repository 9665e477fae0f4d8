// A watertight triangle mesh of a PatchSet whose every vertex carries the exact normal and
// curvature of the limit surface there (evaluatePatch), for the tessellation formats (PLY, glb:
// docs/formats.md, Tessellations).
//
// Each patch is sampled on an (N+1) x (N+1) grid of its parameter square. What makes it watertight:
//  * Seams: samples on a patch's border are welded across patches by a spatial hash (tolerance
//    kWeldTolerance of the bounding-box diagonal); inside one patch by their parameter (exact).
//  * T-junctions (Patch::edgeLevelDelta d > 0 on edge s: 2^d finer patches across it): the coarse
//    side samples that edge with 2^d N segments, which are the fine sides' own samples (the shared
//    curve, refined by knot insertion, keeps its parametrisation: transitionEdgeSegments in
//    patch_extraction.h solves the same problem on the GPU). A grid cell with such a refined side
//    gets a vertex at its centre and is fanned from it.
//  * Where the fine side mixes levels (the coarse side is sampled for the finest of them), the
//    boundary edges left over are split at their parameter midpoints while the midpoint's
//    evaluation welds to an existing vertex (the coarse side's extra sample).
//  * Pole caps: the u = 0 row of every cap is one vertex (the pole); triangles that would use it
//    twice are dropped, so the first ring of cells is a fan of proper triangles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/spline/patch_extraction.h"

namespace polarview {

// Welding distance relative to the bounding-box diagonal: far above the round-off of two patches
// evaluating one seam point (~1e-15), far below the sample spacing of any level an export reaches.
constexpr double kWeldTolerance = 1e-9;

// Where a vertex was evaluated: patch index in the PatchSet, parameter (u,v).
struct TessellationSource {
  uint32_t patch = 0;
  double u = 0.0, v = 0.0;
};

struct Tessellation {
  // Per vertex (parallel): absolute position, unit normal, K, H, where it was evaluated.
  std::vector<Point> positions, normals;
  std::vector<double> gaussian, mean;
  std::vector<TessellationSource> sources;
  // Counter-clockwise seen from the normal's side (du x dv of the patches).
  std::vector<std::array<uint32_t, 3>> triangles;
  int samples = 0;            // N: segments along a patch edge of the same level as its neighbours
  size_t splitEdges = 0;      // boundary edges split at mixed-level T-junctions (the third bullet)
};

// Samples every patch of `set` with `samples` (>= 1) segments per edge and welds it into one mesh
// (rules above). Throws std::invalid_argument for samples < 1 and std::length_error past 2^32 - 1
// vertices. [O(patches x samples^2)]
Tessellation tessellatePatchSet(const PatchSet& set, int samples);

// How the triangles use their edges (an edge: an unordered vertex pair).
struct TessellationEdges {
  size_t edges = 0;
  size_t boundary = 0;      // used by one triangle
  size_t nonManifold = 0;   // used by three or more
  size_t misoriented = 0;   // used twice in the same direction (the two triangles disagree)
  // Every edge used twice, once each way: a closed, consistently oriented surface.
  bool watertight() const { return boundary == 0 && nonManifold == 0 && misoriented == 0; }
};
// Counts the edges of `mesh`'s triangles. [O(triangles log triangles)]
TessellationEdges countTessellationEdges(const Tessellation& mesh);

}  // namespace polarview
