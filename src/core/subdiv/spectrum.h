// Spectra of subdivision matrices: the paper's Table 1 (RTS, Section 5.2: 1, 1/2, 1/2, 1/4, 1/4,
// 1/4 for every n >= 5), BPS's, and Catmull-Clark's at a valence-n vertex. A valence-preserving
// polar scheme's matrix (13) is block circulant, so its spectrum is that of its n Fourier blocks
// (6 x 6 each); Catmull-Clark's 1-ring matrix is small enough to be solved whole. C2PS doubles the
// valence every step and has no stationary matrix (its analysis goes through RTS).
#pragma once

#include <complex>
#include <functional>
#include <vector>

#include "core/subdiv/polar_grid.h"
#include "core/subdiv/scheme.h"

namespace polarview {

using Matrix = std::vector<std::vector<double>>;
using Complex = std::complex<double>;
using ComplexMatrix = std::vector<std::vector<Complex>>;

// Row/column of q_{link, column} in the matrix (13): q = [q_{0,0}, .., q_{5,0}, q_{0,1}, .., q_{5,n-1}].
inline int polarMatrixIndex(int link, int column) { return 6 * column + link; }

// The subdivision matrix (13) of a valence-preserving polar scheme on links 0..5, the pole listed
// once per column (q_{0j} = q00). Column (h, c) is `refine` applied to the unit input at q_{c,h};
// the pole's column is split evenly among its n copies, as in (13). [O(n^2) refinements of O(n)]
Matrix polarSubdivisionMatrix(int n, const std::function<PolarGrid(const PolarGrid&)>& refine);

// Fourier block hat A_alpha = sum_h omega^{h alpha} A_{0h}: A maps v_h = v^ omega^{h alpha} to
// (hat A_alpha v^) omega^{j alpha} when A is block circulant, so the blocks' spectra make A's. [O(n)]
ComplexMatrix fourierBlock(const Matrix& a, int n, int alpha);

// Eigenvalues of a small complex matrix: Householder reduction to Hessenberg form, then QR steps
// with Wilkinson shifts and deflation. Throws std::runtime_error if QR does not converge. [O(size^3)]
std::vector<Complex> eigenvalues(ComplexMatrix h);

// An eigenvalue with the Fourier block it belongs to (alpha; -1 where not block circulant).
struct TaggedEigenvalue {
  Complex value;
  int alpha;
};
// All eigenvalues of a block-circulant (13) matrix via its n Fourier blocks, sorted by decreasing
// modulus. [O(n^2)]
std::vector<TaggedEigenvalue> spectrumByFourierBlocks(const Matrix& a, int n);

// Catmull-Clark's subdivision matrix on the 1-ring of a valence-n interior vertex surrounded by
// quads: rows and columns v, e_0..e_{n-1} (spoke ends), f_0..f_{n-1} (far corners of the quads),
// built from computeCatmullClarkPoints (OpenSubdiv's rules). [O(n^2)]
Matrix catmullClarkRingMatrix(int n);

// The spectrum of `scheme` (RTS, BPS: matrix (13); Catmull-Clark: the 1-ring matrix) at valence n,
// by decreasing modulus. Throws std::invalid_argument for C2PS. [O(n^3) at most]
std::vector<TaggedEigenvalue> schemeSpectrum(Scheme scheme, int n);

}  // namespace polarview
