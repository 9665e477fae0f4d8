// Refiner: drives a scheme over L levels. Topology (meshes, tables, polar configurations) is built
// once; positions can be recomputed from new base points without touching topology.
//
// Level m+1 from level m:
//  * Catmull-Clark everywhere (catmull_clark.h), child vertices ordered
//    [face points | edge points | vertex points] as in OpenSubdiv. With Scheme::CatmullClark the
//    base mesh's crease and corner tags are applied (OpenSubdiv's CREASE_UNIFORM rules) and each
//    level's mesh carries its own, decremented, tags.
//  * C2PS: at each refinable polar configuration the five CC point groups (docs/schemes.md, C2PS
//    inside Catmull-Clark) are overridden by rules (1)-(3) and each pole-corner quad is split along
//    its diagonal, so the polar valence doubles.
//  * RTS / BPS: on meshes made only of polar configurations (caps, globes) the mesh is refined
//    radially with the valence fixed (Figs 3d, 10): `radialOnly()` is true. Where a polar region
//    borders Catmull-Clark mesh, level m has C2PS's connectivity (CC elsewhere) and the polar region
//    (links 0..K_m-1 of the radially refined configuration) holds the radial refinement refined
//    m times periodically by (5): exact knot insertion, so the spline rings are the scheme's own
//    (paper Fig. 5: "BPS refines radially k times, then periodically k times").
#pragma once

#include <memory>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refined_level.h"
#include "core/subdiv/scheme.h"

namespace polarview {

class Refinement {
 public:
  // Refines `base` (already validated) `options.levels` times. Throws InputError when a level would
  // exceed the memory budget (`maxFaces` faces at the finest level). A non-manifold `base` is
  // refined as its manifold split (manifold_split.h, OpenSubdiv's points): level 0 is the split
  // mesh; updatePositions still takes the input's points, and outputMesh merges the copies back.
  Refinement(const PolyMesh& base, const RefineOptions& options, const std::string& sourceName = "<mesh>",
             size_t maxFaces = size_t(1) << 26);
  ~Refinement();
  Refinement(Refinement&&) noexcept;
  Refinement& operator=(Refinement&&) noexcept;

  const RefineOptions& options() const { return options_; }
  int levelCount() const { return int(levels_.size()); }  // levels + 1 (level 0 is the base)
  const RefinedLevel& level(int m) const { return levels_[m]; }
  const RefinedLevel& finest() const { return levels_.back(); }
  // True when RTS/BPS refined the whole mesh radially (valence fixed; caps and globes).
  bool radialOnly() const;

  // Whether the input was non-manifold and level 0 is its manifold split. [O(1)]
  bool splitInput() const;
  // The finest level as the input's refinement: the split's copies of one vertex, edge or face
  // point merged back (OpenSubdiv's vertices, but for the two halves of an edge whose ends are one
  // vertex, which merge), tags mapped. The finest mesh itself when nothing was split.
  // [O(corners of all levels)]
  PolyMesh outputMesh() const;
  // outputMesh, the finest mesh moved out when nothing was split (no copy at the memory limit):
  // the Refinement is spent. [O(1) unsplit]
  PolyMesh takeOutputMesh() &&;

  // Whether the finest level has all its tables (RefineOptions::fullFinestTopology, or
  // completeFinestTopology since). Extracting patches, its edges or walking around its vertices need them.
  bool finestTopologyComplete() const;
  // Builds the finest level's edges and vertex rings when they were left out; then its MeshTopology
  // equals buildTopology(finest mesh). [O(corners of the finest level)]
  void completeFinestTopology();

  // Recomputes every level's points from new base points (same count as the base, else
  // std::invalid_argument). [O(output)]
  void updatePositions(const std::vector<Point>& basePoints);

 private:
  struct Plan;  // per-level rules tables
  RefineOptions options_;
  std::vector<RefinedLevel> levels_;
  std::unique_ptr<Plan> plan_;
};

// Faces the finest level would have (cheap estimate from the base mesh, used for the budget):
// Catmull-Clark growth (x4 a level), or x2 a level where RTS/BPS refine the whole mesh radially
// (`radial`: refinesRadially). [O(1)]
size_t estimateFaceCount(const PolyMesh& base, const RefineOptions& options, bool radial = false);
// True when `scheme` (RTS or BPS) refines all of `base` radially: a cap or globe made of polar
// configurations only (Refinement::radialOnly before refining). [O(mesh)]
bool refinesRadially(const PolyMesh& base, Scheme scheme);
// The same for a prepared base (a split one too: what the refiners refine radially). [O(mesh)]
bool refinesRadially(const PreparedBase& base, Scheme scheme);

}  // namespace polarview
