// What a model's faces determine, made once per loaded mesh and owned by the Model
// (model.h: makeModel): the mesh refinements start from and its tables, its polar
// configurations, whether RTS/BPS refine it radially, whether each scheme refines a pole, and the
// face estimates behind the level limit. Copies of the Model (the viewer hands them to worker
// threads) share one analysis; an edit keeps it: none of it reads the points (the tables, polar
// detection and the estimate's refinement are functions of the faces and tags only).
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/mesh/manifold_split.h"
#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"
#include "pipeline/scheme_choice.h"

namespace polarview {

// Levels the face estimate refines (estimateAdaptiveFaceCounts' `measured`) for the level limit of
// the viewer's slider; a check of one level L measures min(L, this) only.
constexpr int kMeasuredLevels = 7;

class ModelAnalysis {
 public:
  // Builds the tables of `mesh` (of its manifold split where it is not manifold) and finds its
  // polar configurations. Never throws for bad input: a mesh that cannot be refined keeps the
  // reason (error()), refines no pole and estimates 0 faces (building says why).
  // [O(corners log corners)]
  ModelAnalysis(const PolyMesh& mesh, const std::string& name);

  // Empty when the mesh can be refined, else refinableMesh's message. [O(1)]
  const std::string& error() const { return error_; }
  // The mesh refinements start from: `mesh` itself, or its manifold split. Only its faces and tags
  // are the model's (a split mesh keeps the points of the mesh analysed). [O(1)]
  const PolyMesh& refinableMesh(const PolyMesh& mesh) const { return split_.empty() ? mesh : split_.mesh; }
  const ManifoldSplit& split() const { return split_; }
  const MeshTopology& topology() const { return topology_; }           // of refinableMesh
  const std::vector<PolarConfig>& polarConfigs() const { return configs_; }  // findPolarConfigs, all
  // The above for AdaptiveRefinement and the estimate (no tables built again). [O(1)]
  PreparedBase preparedBase(const PolyMesh& mesh) const {
    return PreparedBase{refinableMesh(mesh), split_.sourceVertex, topology_, configs_};
  }
  // RTS/BPS refine the whole mesh radially (a cap or globe of poles only: faces x2 a level, not x4).
  bool radialForRtsBps() const { return radial_; }
  // Whether `scheme` refines some polar configuration of the model. [O(1)]
  bool refinesPoles(Scheme scheme) const { return refinesPoles_[size_t(scheme)]; }

  // The faces the feature-adaptive refinement of `scheme` holds at `level` of `mesh` (this
  // analysis' mesh or an edit of it; all levels together), faceBudget + 1 for a level over the
  // budget. Measured once per scheme and budget to at least `measured` levels (or to the first
  // level over the budget), deepened when a later call needs more: the level limit is asked for
  // every frame, and a command asking for level 1 of a 10^5-valence cap must not make levels 2..7
  // (under the command line's budget that took 17 s and 8 GB). Thread-safe. [O(1) once measured]
  size_t estimatedFaces(const PolyMesh& mesh, SchemeChoice scheme, int level, size_t faceBudget,
                        int measured = kMeasuredLevels) const;

 private:
  struct Estimate {
    std::vector<size_t> totals;
    int measured = -1;
    bool over = false;  // a measured level was over the budget: deeper measuring changes nothing
  };
  std::string error_;
  ManifoldSplit split_;
  MeshTopology topology_;
  std::vector<PolarConfig> configs_;
  bool radial_ = false;
  std::array<bool, std::tuple_size_v<std::decay_t<decltype(schemeTable())>>> refinesPoles_{};  // by Scheme
  mutable std::mutex mutex_;            // guards estimates_
  mutable std::map<std::pair<int, size_t>, Estimate> estimates_;  // by (SchemeChoice, budget)
};

}  // namespace polarview
