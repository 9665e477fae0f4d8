// One level of a refinement (its control mesh, tables, poles and their Taylor data) and the base
// mesh refinements start from: what the Refinement (refiner.h), the feature-adaptive refinement
// (adaptive_refiner.h) and their single steps (refine_steps.h) share.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/spline/pole_taylor.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/polar_grid.h"

namespace polarview {

// A base mesh prepared for refinement once, so that refinements and estimates of one model build
// no tables again (a viewer's model keeps it: pipeline/model_analysis.h): the mesh they start from
// (refinableMesh: the input or its manifold split; its points are not read), the split's vertex
// map (empty when nothing was split), its tables, and every configuration findPolarConfigs finds.
struct PreparedBase {
  const PolyMesh& mesh;
  const std::vector<Index>& sourceVertex;
  const MeshTopology& topology;
  const std::vector<PolarConfig>& configs;
};

struct RefinedLevel {
  PolyMesh mesh;                   // control mesh of this level
  MeshTopology topology;
  std::vector<Index> faceParent;   // per face: parent face at level-1 (empty at level 0)
  // Catmull-Clark only: the sharpness of this level's creases and corners (the base mesh's `t`
  // tags, 1 less a level); empty when nothing is sharp but the boundary.
  CreaseSharpness sharpness;
  // Per face: 1 when it is a hole (baseHoles; children of holes are holes): refined like any face,
  // no patch. Empty when there is none.
  std::vector<uint8_t> faceHole;
  bool isHole(Index f) const { return !faceHole.empty() && faceHole[size_t(f)]; }
  std::vector<PolarConfig> poles;  // polar configurations the scheme treats as poles here
  // Parallel to `poles` (filled for C2PS, RTS and BPS; empty for CC): the pole's points in
  // PolarGrid order (links 0..3 of this level's mesh) and the scheme's Taylor expansion (32) in
  // this level's radial unit (link i at r = i), from which the viewer closes the hole.
  std::vector<PolarGrid> poleGrids;
  std::vector<TaylorCoefficients> poleTaylor;
  // Feature-adaptive levels >= 1 (adaptive_refiner.h, Precision): mesh.points, poleGrids and
  // poleTaylor's p0 are relative to the origin of their vertex's frame, one frame per connected
  // part of the level, so deep rings keep double precision relative to their own size. Empty:
  // absolute (the uniform refinement; level 0).
  std::vector<Point> frameOrigins;
  std::vector<uint32_t> vertexFrame;  // per vertex, index into frameOrigins

  // The origin vertex v's point is relative to. [O(1)]
  Point origin(Index v) const { return frameOrigins.empty() ? Point(0.0) : frameOrigins[vertexFrame[size_t(v)]]; }
  // Vertex v's point in absolute coordinates (rounded to double there). [O(1)]
  Point absolutePoint(Index v) const { return origin(v) + mesh.points[size_t(v)]; }
};

}  // namespace polarview
