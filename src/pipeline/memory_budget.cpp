#include "pipeline/memory_budget.h"

#include <cstdio>
#include <fstream>
#include <vector>

#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/refiner.h"

namespace polarview {

size_t memoryBudgetBytes(size_t requested) {
  if (requested > 0) return requested;
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  size_t kilobytes = 0;
  while (meminfo >> key >> kilobytes) {
    if (key == "MemAvailable:") return size_t(0.8 * double(kilobytes) * 1024.0);
    meminfo.ignore(1 << 10, '\n');
  }
  return size_t(4) << 30;
}

namespace {

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

// The refusal of a level over the memory budget: what it would need, the budget, where the budget
// comes from, and the deepest level that fits.
BudgetRefusal budgetRefusal(const std::string& source, int level, bool requested, size_t budget, const std::string& needed,
                            int fits) {
  return BudgetRefusal(source, 0,
                       "level " + std::to_string(level) + " would need " + needed + ", over the memory budget of " +
                           gigabytes(double(budget)) +
                           (requested ? " (--memory-budget)" : " (80% of the available memory; --memory-budget SIZE to change)") +
                           ": level " + std::to_string(fits) + " fits");
}

}  // namespace

// Faces cost kBytesPerUniformFace (uniform) or kBytesPerAdaptiveFace (memory_budget.h, measured).
size_t checkMemoryBudget(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, size_t requested,
                         bool adaptive) {
  const size_t budget = memoryBudgetBytes(requested);
  auto refusal = [&](const std::string& needed, int fits) {
    return budgetRefusal(source, options.levels, requested > 0, budget, needed, fits);
  };
  const bool radial = refinesRadially(mesh, options.scheme);  // (checks the mesh for either path)
  if (!adaptive) {
    const UniformLevelEstimate e = estimateUniformLevel(mesh, options, radial, budget / kBytesPerUniformFace);
    if (!e.fits) throw refusal("about " + gigabytes(double(e.faces) * kBytesPerUniformFace), e.deepestFitting);
    return size_t(double(budget) / double(kBytesPerUniformFace));
  }
  // The feature-adaptive estimate stops past the budget: "more than" the budget there.
  const size_t budgetFaces = budget / kBytesPerAdaptiveFace;
  const std::vector<size_t> faces = estimateAdaptiveFaceCounts(mesh, options, budgetFaces);
  auto bytesAt = [&](int level) { return double(faces[size_t(level)]) * kBytesPerAdaptiveFace; };
  if (bytesAt(options.levels) > double(budget)) {
    int fits = options.levels;
    while (fits > 0 && bytesAt(fits) > double(budget)) --fits;
    const bool beyondEstimate = faces[size_t(options.levels)] == budgetFaces + 1;
    throw refusal(beyondEstimate ? "more than " + gigabytes(double(budget)) : "about " + gigabytes(bytesAt(options.levels)), fits);
  }
  return size_t(double(budget) / double(kBytesPerAdaptiveFace));
}

UniformLevelEstimate estimateUniformLevel(const PolyMesh& mesh, const RefineOptions& options, bool radial, size_t maxFaces) {
  auto facesAt = [&](int level) {
    RefineOptions at = options;
    at.levels = level;
    return estimateFaceCount(mesh, at, radial);
  };
  UniformLevelEstimate estimate{facesAt(options.levels), options.levels, true};
  estimate.fits = estimate.faces <= maxFaces;
  while (estimate.deepestFitting > 0 && facesAt(estimate.deepestFitting) > maxFaces) --estimate.deepestFitting;
  return estimate;
}

}  // namespace polarview
