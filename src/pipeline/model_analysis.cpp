#include "pipeline/model_analysis.h"

#include <algorithm>
#include <exception>

#include "core/subdiv/adaptive_refiner.h"

namespace polarview {

ModelAnalysis::ModelAnalysis(const PolyMesh& mesh, const std::string& name) {
  try {
    // Non-manifold meshes are refined as their split (manifold_split.h).
    const PolyMesh& base = polarview::refinableMesh(mesh, split_, topology_, name);
    configs_ = findPolarConfigs(base, topology_);
  } catch (const std::exception& e) {
    error_ = e.what();  // not refinable: nothing below applies
    split_ = ManifoldSplit{};
    topology_ = MeshTopology{};
    return;
  }
  const PreparedBase base = preparedBase(mesh);
  radial_ = refinesRadially(base, Scheme::RTS);  // RTS and BPS refine the same poles (n >= 5)
  for (const SchemeTraits& traits : schemeTable())
    refinesPoles_[size_t(traits.scheme)] =
        std::any_of(configs_.begin(), configs_.end(), [&](const PolarConfig& c) { return schemeRefinesPole(traits.scheme, c); });
}

size_t ModelAnalysis::estimatedFaces(const PolyMesh& mesh, SchemeChoice scheme, int level, size_t faceBudget,
                                     int measured) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  Estimate& estimate = estimates_[{int(scheme), faceBudget}];
  measured = std::clamp(measured, 1, kMeasuredLevels);
  if (estimate.measured < measured && !estimate.over) {
    bool made = false;
    try {
      // Bounded by the budget: a level over it is not made (it reads budget + 1), however large the input.
      if (error_.empty()) {
        estimate.totals = estimateAdaptiveFaceCounts(mesh, preparedBase(mesh), refineOptionsFor(scheme, kMaxLevel), faceBudget, measured);
        made = true;
      }
    } catch (const std::exception&) {
      // out of memory: as not refinable
    }
    if (!made) estimate.totals.assign(size_t(kMaxLevel) + 1, 0);  // not refinable: building says why
    estimate.over = !made || std::find(estimate.totals.begin(), estimate.totals.end(), faceBudget + 1) != estimate.totals.end();
    estimate.measured = measured;
  }
  return estimate.totals[size_t(std::clamp(level, 0, kMaxLevel))];
}

}  // namespace polarview
