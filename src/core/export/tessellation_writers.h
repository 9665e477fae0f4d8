// The tessellation formats (docs/formats.md, PLY and glb): a Tessellation with its exact normals,
// K and H, and a colour per vertex chosen by the caller (the pipeline maps K through the viewer's
// colour map; the core knows no colour maps).
#pragma once

#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "core/export/tessellation.h"

namespace polarview {

// What the files say besides the mesh.
struct TessellationFileInfo {
  std::string source = "<patches>";  // the input's name: in headers and in error messages
  std::string schemeLabel;           // "C2PS", ...
  int level = 0;
  std::vector<glm::vec3> colours;    // per vertex, sRGB in [0, 1] (as a colour map gives them)
  std::string colouring;             // what the colours show, e.g. "K, paper map over [-2.5, 2.5]"
};

// Binary little-endian PLY: vertex x y z nx ny nz quality gaussian_curvature mean_curvature (double;
// quality = K), red green blue (uchar); face vertex_indices (list uchar int). Throws InputError
// (info.source) for a non-finite value or a colour count that is not the vertex count, before any
// byte is made. [O(vertices + triangles)]
std::string plyBytes(const Tessellation& mesh, const TessellationFileInfo& info);
// glTF 2.0 binary: one mesh, one indexed TRIANGLES primitive with POSITION (float, min/max), NORMAL,
// COLOR_0 (float RGB, linear: the sRGB colours decoded), _GAUSSIAN_CURVATURE and _MEAN_CURVATURE
// (float SCALAR), uint32 indices; asset.generator "polarview", asset.extras name source, scheme,
// level, samples and colouring. Throws InputError as plyBytes, and for values past float's range.
// [O(vertices + triangles)]
std::string glbBytes(const Tessellation& mesh, const TessellationFileInfo& info);

}  // namespace polarview
