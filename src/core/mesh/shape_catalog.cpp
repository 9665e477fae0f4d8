#include "core/mesh/shape_catalog.h"

#include <algorithm>
#include <stdexcept>

#include "core/mesh/figure_shapes.h"
#include "core/mesh/shapes.h"

namespace polarview::shapes {

const std::vector<std::string>& shapeNames() {
  static const std::vector<std::string> names{"globe", "cap", "mushroom", "cube", "torus", "valence20", "fingertips"};
  return names;
}

const std::vector<std::string>& heightNames() {
  static const std::vector<std::string> names{"paraboloid", "saddle", "monkey", "flat4", "saddle4", "convex", "cone"};
  return names;
}

std::string joinNames(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

PolyMesh makeNamedShape(const ShapeRequest& o) {
  const std::string& name = o.name;
  const std::vector<std::string>& known = shapeNames();
  if (std::find(known.begin(), known.end(), name) == known.end())
    throw std::invalid_argument("unknown shape '" + name + "' (" + joinNames(known, ", ") + ")");
  if (!o.height.empty() && name != "cap") throw std::invalid_argument("--height applies to the cap");
  if (name == "globe") return globe(o.valence, o.links);
  if (name == "cap" && !o.height.empty()) {
    const auto function = paperHeight(o.height);
    if (!function) throw std::invalid_argument("unknown height '" + o.height + "' (" + joinNames(heightNames(), ", ") + ")");
    return heightCap(o.valence, o.links, function);
  }
  if (name == "cap") return polarCap(o.valence, o.links);
  if (name == "mushroom") {
    if (o.valence % 4) throw std::invalid_argument("the mushroom needs a valence divisible by 4");
    return mushroom(o.valence);
  }
  if (name == "cube") return cube();
  if (name == "torus") return torus(o.valence, o.links);
  // The paper's Figs. 12 and 2c: fixed configurations (figure_shapes.h).
  if (o.sized) throw std::invalid_argument("--valence and --links do not apply to " + name);
  return name == "valence20" ? valence20Bump() : fingertips();
}

}  // namespace polarview::shapes
