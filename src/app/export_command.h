// `polarview export`: the limit surface as Bezier patches in BezierView's .bv format
// (core/spline/bezierview_export.h says what is written and how exact it is).
#pragma once

#include <string>

#include "app/cli_commands.h"
#include "core/spline/patch_extraction.h"

namespace polarview::cli {

// polarview export IN.obj --scheme S --level L -o OUT.bv [--uniform] [--memory-budget SIZE]
// Exit codes as cli_commands.h; the output is written atomically (nothing on any error).
int runExport(const Args& args);

// The patches `export` writes: `uniform` refines every face to options.levels (Refinement) and
// extracts feature-adaptively (extractPatches); the adaptive path does the same for now.
// Throws InputError for bad meshes and levels over the refiner's face limit.
PatchSet exportPatchSet(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, bool uniform);

}  // namespace polarview::cli
