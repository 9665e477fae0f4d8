// What the commands, the Python module and the viewer make of a mesh to hand out or write: the
// limit surface's patches, the refined control mesh, each within a budget: a memory budget refuses
// a level before anything is allocated (memory_budget.h); a face budget is the caller's to check
// first (the viewer's level limit) and the refiner's hard limit.
#pragma once

#include <cstddef>
#include <string>

#include "core/spline/patch_extraction.h"

namespace polarview {

// The patches `export` writes: feature-adaptive refinement (AdaptiveRefinement, the path of view
// and render), or with `uniform` every face refined to options.levels (Refinement); both give the
// same patches (tests/core/adaptive_refiner_test.cpp). Throws InputError for bad meshes and levels
// over `maxFaces`. [O(output)]
PatchSet exportPatchSet(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, bool uniform,
                        size_t maxFaces);

// Which refinement a patch set comes from: the feature-adaptive one (view, render, export's default)
// or every face refined (export --uniform); both give the same patches.
enum class RefinePath { FeatureAdaptive, Uniform };

// What a caller asks to be refined, and what it may take: a memory budget (the commands, Python) or
// a face limit it has checked itself (the viewer's level limit).
struct RefineRequest {
  RefineOptions options;
  RefinePath path = RefinePath::FeatureAdaptive;  // patches only: a refined mesh is always uniform
  size_t memoryBudget = 0;  // bytes, as --memory-budget (0: memory_budget.h's default)
  size_t faceBudget = 0;    // when > 0, a face limit instead

  static RefineRequest withinMemory(const RefineOptions& options, RefinePath path, size_t bytes) {
    return {options, path, bytes, 0};
  }
  static RefineRequest withinFaces(const RefineOptions& options, RefinePath path, size_t faces) {
    return {options, path, 0, faces};
  }
};

// The patches of `request`: refused (BudgetRefusal, naming `source` and the deepest level that fits)
// before any allocation when over the memory budget; the feature-adaptive path's hard limit is twice
// its estimate (an extrapolation past level 6). `export`, `continuity`, limit_patches() and the
// viewer's Export surface. [O(output)]
PatchSet makePatchSet(const PolyMesh& mesh, const std::string& source, const RefineRequest& request);

// The control mesh after options.levels uniform steps (a non-manifold input was refined split: its
// copies merge back), refused as makePatchSet's uniform path. `refine`, refine() and the viewer's
// Export refined OBJ. [O(output)]
PolyMesh makeRefinedMesh(const PolyMesh& mesh, const std::string& source, const RefineRequest& request);

}  // namespace polarview
