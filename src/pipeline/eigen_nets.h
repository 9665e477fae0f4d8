// Fig. 1's eigenvector nets as meshes (figure 1 and the viewer's Spectrum panel).
#pragma once

#include "core/mesh/poly_mesh.h"

namespace polarview {

// Fig. 1's nets: links 0..5 of the valence-n polar configuration whose point q_ij is
// (v1, v2, v_k)_ij, the right eigenvectors of RTS (spectrum.h) over the characteristic map (v1, v2),
// z = 0 for k <= 2 (chi itself). For k >= 3 without steps the planar net of chi lies below it (the
// paper's disk), a second component.
// `steps` > 0: that many C2PS steps first (links 0..5 kept, the valence doubling), then magnified
// back by 2^steps in x, y and lambda_k^-steps in z, so that Lemma 5's scaling shows as equal heights.
// [O(n^2) for the eigenpairs + O(steps n 2^steps)]
PolyMesh eigenNet(int n, int k, int steps);

}  // namespace polarview
