// Blender's "triangle fan" cap fill as a conversion: every face of at least kMinFanSides corners
// becomes a fan of triangles around a new vertex at its centroid. A cylinder or a cone made with
// n-gon caps has no polar configuration (a pole is the centre of a fan of triangles, ringed by
// quads: core/subdiv/polar_config.h); after the conversion each cap's centre is an n-valent pole
// candidate, and a pole where the rim is ringed by quads (a Blender cylinder's sides).
//
// Quads and triangles stay as they are (a quad is regular Catmull-Clark, a fan of 4 would not be a
// useful pole). Triangle i of the fan is (loop[i], loop[i+1], centre): it keeps the face's winding,
// so it is oriented as the face's neighbours are. (A strongly non-convex face's centroid may lie
// outside it, and its fan folds over, as Blender's does.) Vertex ids are kept (centres are
// appended), so creases and corners (`t` tags) stay; hole faces are not converted (no surface
// there), and their ids follow the faces' new numbering.
#pragma once

#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

// The fewest corners a face needs to become a fan: 5 (a pentagon's fan is a 5-valent pole, the
// least RTS and BPS refine; C2PS takes 3 and up, but triangles and quads are no caps).
constexpr int kMinFanSides = 5;

struct FanConversion {
  PolyMesh mesh;
  std::vector<Index> centres;  // the new fan centres, ids in `mesh`, in the order of the faces converted
  std::vector<Index> faces;    // the faces converted (ids in the input)
};

// Replaces each face with at least `minSides` corners (hole faces excepted) by a fan of triangles
// around its centroid, in place in the face order; other faces, tags and source lines are kept.
// [O(mesh)]
FanConversion convertNgonsToFans(const PolyMesh& mesh, int minSides = kMinFanSides);

// How many faces convertNgonsToFans would convert. [O(faces)]
int countFanFaces(const PolyMesh& mesh, int minSides = kMinFanSides);

}  // namespace polarview
