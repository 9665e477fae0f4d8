#include "pipeline/level_limits.h"

#include <algorithm>
#include <string>

#include "pipeline/model_analysis.h"

namespace polarview {

namespace {
// The model's face estimate (ModelAnalysis::estimatedFaces, measured to `measured` levels).
size_t estimatedFaces(const Model& model, SchemeChoice scheme, int level, size_t faceBudget, int measured = kMeasuredLevels) {
  return analysisOf(model).estimatedFaces(*model.mesh, scheme, level, faceBudget, measured);
}

// The deepest level whose estimate (measured to `measured` levels) fits the budget.
int deepestMeasuredLevel(const Model& model, SchemeChoice scheme, size_t faceBudget, int measured) {
  int level = 0;
  while (level < kMaxLevel && estimatedFaces(model, scheme, level + 1, faceBudget, measured) <= faceBudget) ++level;
  return level;
}
}  // namespace

size_t estimatedLevelFaces(const Model& model, SchemeChoice scheme, int level, size_t faceBudget) {
  return estimatedFaces(model, scheme, level, faceBudget);
}

int patchLevelFor(const Model& model, SchemeChoice scheme, int level, size_t faceBudget) {
  const Scheme refined = refineOptionsFor(scheme, level).scheme;
  const SchemeTraits& traits = schemeTraits(refined);
  if (!traits.polar() || traits.curvatureContinuous || level >= kNonC2CapLevel || !model.mesh || !analysisOf(model).refinesPoles(refined))
    return level;
  return std::max(level, std::min(kNonC2CapLevel, deepestLevel(model, scheme, faceBudget)));
}

int deepestLevel(const Model& model, SchemeChoice scheme, size_t faceBudget) {
  return deepestMeasuredLevel(model, scheme, faceBudget, kMeasuredLevels);
}

std::string levelRefusal(const Model& model, SchemeChoice scheme, int level, size_t faceBudget) {
  // Whether `level` fits needs the levels up to it measured, no deeper: the deepest level below it is
  // among them when it does not.
  const int measured = std::min(std::max(level, 1), kMeasuredLevels);
  const int deepest = deepestMeasuredLevel(model, scheme, faceBudget, measured);
  if (level <= deepest) return {};
  std::string text = "level " + std::to_string(level) + " refused: " + schemeChoiceLabel(scheme) +
                     " stops at level " + std::to_string(deepest) + " on this model";
  if (deepest < kMaxLevel) {
    const size_t faces = estimatedFaces(model, scheme, deepest + 1, faceBudget, measured);
    text += " (level " + std::to_string(deepest + 1) + " would make " +
            (faces == faceBudget + 1 ? "more than " + std::to_string(faceBudget) : "about " + std::to_string(faces)) +
            " faces, over the budget of " + std::to_string(faceBudget) + ")";
  } else {
    text += " (the deepest level polarview offers)";
  }
  return text;
}

std::string checkFaceBudget(const Model& model, const SurfaceKey& key, size_t faceBudget) {
  return levelRefusal(model, key.scheme, key.level, faceBudget);
}

}  // namespace polarview
