// The limit surface as Bezier patches in BezierView's .bv format, as `polarview export` and the
// viewer's Export .bv write it
// (core/spline/bezierview_export.h says what is written and how exact it is).
#pragma once

#include <string>

#include "core/spline/bezierview_export.h"
#include "core/spline/patch_extraction.h"

namespace polarview {

// The patches `export` writes: feature-adaptive refinement (AdaptiveRefinement, the path of view
// and render), or with `uniform` every face refined to options.levels (Refinement); both give the
// same patches (tests/core/adaptive_refiner_test.cpp). Throws InputError for bad meshes and levels
// over `maxFaces`. [O(output)]
PatchSet exportPatchSet(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, bool uniform,
                        size_t maxFaces);

// Writes `set` to `path` atomically (nothing is left on any error) and says what was written.
BezierViewStats writeBezierViewFile(const std::string& path, const PatchSet& set, const std::string& source);

}  // namespace polarview
