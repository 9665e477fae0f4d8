// The limit surface as Bezier patches in BezierView's .bv format, as `polarview export` and the
// viewer's Export .bv write it
// (core/spline/bezierview_export.h says what is written and how exact it is).
#pragma once

#include <functional>
#include <iosfwd>
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

// A uniform refinement's size against a face budget, before any allocation: the faces of the
// finest level (estimateFaceCount; `radial` where RTS/BPS refine the whole mesh radially) and the
// deepest level within `maxFaces`. The uniform refusals read it: refine, bench and export --uniform
// (as bytes, kBytesPerUniformFace a face) and the viewer's refined control mesh. [O(levels x mesh)]
struct UniformLevelEstimate {
  size_t faces = 0;        // at options.levels
  int deepestFitting = 0;  // options.levels itself when it fits
  bool fits = true;
};
UniformLevelEstimate estimateUniformLevel(const PolyMesh& mesh, const RefineOptions& options, bool radial, size_t maxFaces);

// Runs `write` on a stream into an AtomicFileWriter for `path` and commits it: any exception (from
// `write` or the file) leaves nothing behind. The stream throws on bad writes. [O(bytes)]
void writeStreamAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Writes `set` to `path` atomically (nothing is left on any error) and says what was written.
BezierViewStats writeBezierViewFile(const std::string& path, const PatchSet& set, const std::string& source);

}  // namespace polarview
