// The commands' memory budget (docs/precision.md): a level whose estimate needs more than the
// budget is refused before any allocation, naming the deepest level that fits. `refine`, `export`
// and `bench` (CLI) and refine() / limit_patches() (Python module) read it.
#pragma once

#include <cstddef>
#include <string>

#include "core/mesh/input_error.h"
#include "core/mesh/poly_mesh.h"
#include "core/subdiv/scheme.h"

namespace polarview {

// A refusal by the memory budget: bad input like any InputError, told apart where the caller maps
// it to its own out-of-memory error (the Python module's MemoryError).
class BudgetRefusal : public InputError {
 public:
  using InputError::InputError;
};

// What a face costs at peak: of the feature-adaptive refinement (its levels and the patches: peak RSS
// 500-514 bytes a face, C2PS level 12 on the default model, a valence-64 cap at level 10 and
// catmark_car at level 8, `bench --adaptive`; the sparse steps make about 2 faces a patch, so a face
// carries half a patch), and of the finest level of a uniform refinement (`refine`'s measure:
// 236-248 bytes a face, Catmull-Clark on a cube).
constexpr size_t kBytesPerAdaptiveFace = 520;
constexpr size_t kBytesPerUniformFace = 300;

// The memory a refinement may take: `requested` bytes when > 0, else 80% of what the machine has
// available now (MemAvailable), else 4 GiB where that cannot be read. [O(1)]
size_t memoryBudgetBytes(size_t requested);

// Refuses at once (BudgetRefusal naming `source`), before any allocation, a level whose estimated
// memory exceeds the budget (`requested` as memoryBudgetBytes takes it), and names the deepest level
// that fits. Returns the budget as a face count for the refiner: uniform (Refinement) or
// feature-adaptive (`adaptive`, AdaptiveRefinement). [O(levels x mesh)]
size_t checkMemoryBudget(const PolyMesh& mesh, const RefineOptions& options, const std::string& source, size_t requested,
                         bool adaptive = false);

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

}  // namespace polarview
