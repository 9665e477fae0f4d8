// How deep a view may go on a model: the memory a view's surface may take, the face budget that
// follows, the face estimates behind the level limit, and the level whose patches a view shows.
#pragma once

#include <cstddef>
#include <string>

#include "pipeline/memory_budget.h"
#include "pipeline/model.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/surface_key.h"

namespace polarview {

// Memory one view's surface may take while it is built; the face budget of a level (all its adaptive
// levels together) follows at kBytesPerAdaptiveFace (memory_budget.h); above it a level is refused
// with a message. The viewer's "refined control mesh" export refuses levels whose uniform mesh would
// not fit it at kBytesPerUniformFace.
constexpr size_t kViewMemoryBudget = size_t(640) << 20;
constexpr size_t kDefaultFaceBudget = kViewMemoryBudget / kBytesPerAdaptiveFace;

// RTS and BPS are not C2 at the pole, so their Taylor cap (docs/rings-and-pole.md) has a curvature of
// its own, and its seam with the last ring shows as a ring in curvature maps at shallow levels. The
// views close their holes at this level at the least: the rings in between are exact pieces of the
// limit surface (RTS/BPS refine radially: a ring a level), and the cap there spans ~3e-5 of the
// first ring, below a pixel unless the user zooms in (then a deeper level moves it further in).
constexpr int kNonC2CapLevel = 16;

// The faces the feature-adaptive refinement of `scheme` holds at `level` on the model (all levels
// together; the estimate deepestLevel uses); faceBudget + 1 for a level over `faceBudget`, which
// the estimate does not make. [O(1) after the first call per model, scheme and budget]
size_t estimatedLevelFaces(const Model& model, SchemeChoice scheme, int level, size_t faceBudget = kDefaultFaceBudget);
// The level whose patches a view of `scheme` at `level` shows: `level`, or kNonC2CapLevel for
// schemes that are not C2 at the pole when the model has poles they refine (within the budget).
int patchLevelFor(const Model& model, SchemeChoice scheme, int level, size_t faceBudget);
// The deepest level of `scheme` on `mesh` whose estimated faces fit `faceBudget`, at most kMaxLevel:
// the one limit of the level slider, the keys, `view` and `render`. [O(1) per level]
int deepestLevel(const Model& model, SchemeChoice scheme, size_t faceBudget);
// Empty when `level` is within deepestLevel, else the one-line refusal, e.g. "level 24 refused: C2PS
// stops at level 13 on this model (level 14 would make about 1967589 faces, over the budget of 1290555)".
std::string levelRefusal(const Model& model, SchemeChoice scheme, int level, size_t faceBudget);
// Returns the refusal message when `key` would exceed the budget, empty when it fits. [O(mesh)]
std::string checkFaceBudget(const Model& model, const SurfaceKey& key, size_t faceBudget);

}  // namespace polarview
