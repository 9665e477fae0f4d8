// The patches and refined meshes the commands, the Python module and the viewer make (patch_export.h).
#include "pipeline/patch_export.h"

#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/refiner.h"
#include "pipeline/memory_budget.h"

namespace polarview {

PatchSet exportPatchSet(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, bool uniform,
                        size_t maxFaces) {
  if (uniform) return extractPatches(Refinement(mesh, options, source, maxFaces));
  return extractPatches(AdaptiveRefinement(mesh, options, source, maxFaces));
}

namespace {
// The refiner's face limit for `request`: its face budget, or its memory budget's.
size_t faceLimit(const PolyMesh& mesh, const std::string& source, const RefineRequest& request, bool adaptive) {
  if (request.faceBudget > 0) return request.faceBudget;
  return checkMemoryBudget(mesh, request.options, source, request.memoryBudget, adaptive);
}
}  // namespace

PatchSet makePatchSet(const PolyMesh& mesh, const std::string& source, const RefineRequest& request) {
  const bool adaptive = request.path == RefinePath::FeatureAdaptive;
  const size_t maxFaces = faceLimit(mesh, source, request, adaptive) * (adaptive ? 2 : 1);
  return exportPatchSet(mesh, request.options, source, !adaptive, maxFaces);
}

PolyMesh makeRefinedMesh(const PolyMesh& mesh, const std::string& source, const RefineRequest& request) {
  const size_t maxFaces = faceLimit(mesh, source, request, false);
  RefineOptions options = request.options;
  options.fullFinestTopology = false;  // only the finest level's faces and points are handed out
  return Refinement(mesh, options, source, maxFaces).takeOutputMesh();
}

}  // namespace polarview
