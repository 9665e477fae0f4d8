// Crease edges and corners given as lists (the Python module's Mesh(..., crease_edges=...), the
// Blender add-on's edge creases) made into a mesh's SubdivTags with the OBJ reader's rules
// (obj_io.h, `t crease` / `t corner`): ids 0-based and in range, a crease on an edge of some face,
// sharpness finite and >= 0, a later entry for the same edge or vertex overriding an earlier one,
// sharpness 0 left out, sorted.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

// Sets mesh.tags.creases and .corners from the lists (the edges' vertex order does not matter).
// Throws InputError(source, 0, "...") naming the first bad entry; the mesh is unchanged then.
// [O(faces' corners log creases + corners log corners)]
void setSharpFeatures(PolyMesh& mesh, const std::vector<CreaseEdge>& creases, const std::vector<CornerVertex>& corners,
                      const std::string& source);

}  // namespace polarview
