// Refiner: drives a scheme over L levels. Topology (meshes, tables, polar configurations) is built
// once; positions can be recomputed from new base points without touching topology.
//
// Level m+1 from level m:
//  * Catmull-Clark everywhere (catmull_clark.h), child vertices ordered
//    [face points | edge points | vertex points] as in OpenSubdiv.
//  * C2PS: at each refinable polar configuration the five CC point groups of SCHEMES.md section 2 are
//    overridden by rules (1)-(3) and each pole-corner quad is split along its diagonal, so the
//    polar valence doubles.
//  * RTS / BPS: on meshes made only of polar configurations (caps, globes) the mesh is refined
//    radially with the valence fixed (Figs 3d, 10). Elsewhere see README "RTS/BPS next to CC".
#pragma once

#include <memory>
#include <vector>

#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/scheme.h"

namespace polarview {

struct RefinedLevel {
  PolyMesh mesh;                   // control mesh of this level
  MeshTopology topology;
  std::vector<Index> faceParent;   // per face: parent face at level-1 (empty at level 0)
  std::vector<PolarConfig> poles;  // polar configurations the scheme treats as poles here
};

class Refinement {
 public:
  // Refines `base` (already validated) `options.levels` times. Throws InputError when a level would
  // exceed the memory budget (`maxFaces` faces at the finest level).
  Refinement(const PolyMesh& base, const RefineOptions& options, const std::string& sourceName = "<mesh>",
             size_t maxFaces = size_t(1) << 26);
  ~Refinement();
  Refinement(Refinement&&) noexcept;
  Refinement& operator=(Refinement&&) noexcept;

  const RefineOptions& options() const { return options_; }
  int levelCount() const { return int(levels_.size()); }  // levels + 1 (level 0 is the base)
  const RefinedLevel& level(int m) const { return levels_[m]; }
  const RefinedLevel& finest() const { return levels_.back(); }

  // Recomputes every level's points from new base points (same count as the base). [O(output)]
  void updatePositions(const std::vector<Point>& basePoints);

 private:
  struct Plan;  // per-level rules tables
  RefineOptions options_;
  std::vector<RefinedLevel> levels_;
  std::unique_ptr<Plan> plan_;
};

// Faces the finest level would have (cheap estimate from the base mesh, used for the budget). [O(mesh)]
size_t estimateFaceCount(const PolyMesh& base, const RefineOptions& options);

}  // namespace polarview
