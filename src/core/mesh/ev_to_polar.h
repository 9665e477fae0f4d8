// Fig. 14 of Myles & Peters 2009: a Catmull-Clark extraordinary vertex turned into a polar
// configuration, so C2PS can refine it (and CC on the original can be compared with C2PS on the
// converted mesh). For an interior vertex v of valence n != 4 whose n faces are quads
// (v, e_i, f_i, e_{i+1}):
//  * Fig. 14(a) (default): a 2n-valent polar configuration and n 5-valent extraordinary vertices.
//    New points w_i = (v + e_i) / 2 on the spokes and u_i = the centre of quad i make the 1-link
//    w_0, u_0, w_1, u_1, ...; triangles (v, w_i, u_i), (v, u_i, w_{i+1}); each quad becomes
//    (w_i, e_i, f_i, u_i) and (u_i, f_i, e_{i+1}, w_{i+1}). The 2-link is e_0, f_0, e_1, ...; each
//    f_i gains the edge to u_i and becomes 5-valent.
//  * Fig. 14(c) (`pentagons`): an n-valent polar configuration and n pentagons. Points w_i and x_i
//    at 1/3 and 2/3 of each spoke (links 1 and 2); triangles (v, w_i, w_{i+1}), quads
//    (w_i, x_i, x_{i+1}, w_{i+1}); each quad becomes the pentagon (x_i, e_i, f_i, e_{i+1}, x_{i+1}).
// Vertices are converted in id order; one whose quads touch those of a vertex already converted is
// skipped (the regions would overlap), as is one whose ring repeats a vertex.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

struct PolarConversion {
  PolyMesh mesh;
  std::vector<Index> converted;  // the extraordinary vertices turned into poles (same ids in `mesh`)
  std::vector<Index> skipped;    // extraordinary vertices left as they were (overlapping regions)
};

// Converts every interior all-quad extraordinary vertex of `mesh` it can. Throws InputError when
// the mesh is not a valid manifold (buildTopology). [O(mesh)]
PolarConversion convertExtraordinaryToPolar(const PolyMesh& mesh, bool pentagons, const std::string& sourceName = "<mesh>");

}  // namespace polarview
