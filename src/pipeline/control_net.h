// The control net as the views draw it: each edge of the base mesh once, with the sharpness its
// tags give it, so that crease edges (and non-manifold ones, which OpenSubdiv makes infinitely sharp)
// stand out from the smooth cage. GL-free; render/patch_renderer draws it.
#pragma once

#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

struct NetSegment {
  Index a = -1, b = -1;     // vertex ids of the mesh, a < b
  float sharpness = 0.0f;   // 0: smooth; the crease tag's (kInfiniteSharpness: infinitely sharp)
};

// Every edge of `mesh` once (by vertex pair), with its `t crease` sharpness, and infinitely sharp
// where the edge is non-manifold (manifold_split.h). Boundary edges are 0 (they are sharp anyway).
// [O(corners log corners)]
std::vector<NetSegment> controlNetSegments(const PolyMesh& mesh);

// The net's colour of a segment: dark grey when smooth, orange through red as the sharpness grows
// to 3 and beyond. [O(1)]
Point netSegmentColor(float sharpness);

}  // namespace polarview
