// The shapes `polarview shape` and the Python module's shape() make, by name: the parametric meshes
// of shapes.h and the paper's fixed figure inputs of figure_shapes.h.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview::shapes {

// The shape names and the height functions a cap can follow (paperHeight's names), in help order.
const std::vector<std::string>& shapeNames();
const std::vector<std::string>& heightNames();
// The names joined: "globe|cap|..." with separator "|".
std::string joinNames(const std::vector<std::string>& names, const char* separator);

struct ShapeRequest {
  std::string name;
  std::string height;  // cap only: over paperHeight(height); empty: the paraboloid polarCap
  int valence = 12, links = 6;
  bool sized = false;  // valence or links given (the fixed figure shapes refuse them)
};

// The named shape. Throws std::invalid_argument with a one-line reason for an unknown shape or
// height, a height on another shape than the cap, a mushroom valence not divisible by 4, or a
// size given to a fixed shape. [O(output)]
PolyMesh makeNamedShape(const ShapeRequest& request);

}  // namespace polarview::shapes
