// Spectra of subdivision matrices: the paper's Table 1 (RTS, Section 5.2: 1, 1/2, 1/2, 1/4, 1/4,
// 1/4 for every n >= 5, with the right and left eigenvectors), BPS's, and Catmull-Clark's at a
// valence-n vertex. A valence-preserving polar scheme's matrix (13) is block circulant, so its
// eigenpairs are those of its n Fourier blocks (6 x 6 each), mapped back by (14) and (26);
// Catmull-Clark's 1-ring matrix is block circulant (3 x 3) once its centre is listed in every
// column as (13) lists the pole. C2PS doubles the valence every step and has no stationary matrix
// (its analysis goes through RTS; Lemma 5's scaling is checked by c2psEigencoefficientScaling).
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

// A block-circulant matrix in the layout of (13): n columns of b points each (b = size / n), point
// i of column j at row b j + i, point 0 the centre (the pole) listed once per column with its
// matrix column split evenly among the n copies. polarSubdivisionMatrix (b = 6) and
// catmullClarkCirculantMatrix (b = 3) are of this kind; fourierBlock and the functions below take it.

// The subdivision matrix (13) of a valence-preserving polar scheme on links 0..5, the pole listed
// once per column (q_{0j} = q00). Column (h, c) is `refine` applied to the unit input at q_{c,h};
// the pole's column is split evenly among its n copies, as in (13). [O(n^2) refinements of O(n)]
Matrix polarSubdivisionMatrix(int n, const std::function<PolarGrid(const PolarGrid&)>& refine);

// Fourier block hat A_alpha = sum_h omega^{h alpha} A_{0h} (b x b): A maps v_h = v^ omega^{h alpha} to
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
// modulus (equal moduli in block order). `centreOnce`: leave out the n - 1 zero eigenvalues that
// listing the centre n times adds (blocks alpha != 0 have a zero centre row and column), giving the
// spectrum of the matrix with the centre listed once. [O(n^2)]
std::vector<TaggedEigenvalue> spectrumByFourierBlocks(const Matrix& a, int n, bool centreOnce = false);

// How an eigenvector varies over the columns j (op_k of (14)): the same profile in every column
// (alpha = 0, or alpha = n/2 with sign (-1)^j); the cos or sin part of the complex pair of blocks
// alpha, n - alpha (the real basis (14) of their shared 2D eigenspace: Cos for alpha < n/2, Sin for
// alpha > n/2); Complex for a non-real eigenvalue (its own complex vectors).
enum class FourierMode { Single, Cos, Sin, Complex };
const char* fourierModeName(FourierMode mode);  // "single", "cos", "sin", "complex"

// One eigenvalue of a block-circulant matrix with its right eigenvector v (A v = value v) and left
// eigenvector w (w^T A = value w^T), entries in the matrix's order. v's profile (the block's
// eigenvector, Table 1's v^) has largest modulus 1, its first non-negligible entry real and its
// largest entry's real part positive;
// w is scaled so that w_k^T v_l = delta_kl over all pairs of one call (26). Empty vectors where the
// eigenvalue is zero or defective (no basis of eigenvectors: w^T v would vanish).
struct EigenPair {
  Complex value;
  int alpha;  // the Fourier block (for Sin: n - alpha' of the Cos partner's block alpha')
  FourierMode mode;
  std::vector<Complex> right, left;
  std::vector<Complex> rightProfile, leftProfile;  // v^, w^ of block min(alpha, n - alpha), (14), (26)
};

// The eigenpairs of the first `count` entries of `spectrum` (= spectrumByFourierBlocks(a, n)), each
// computed in its b x b Fourier block (the null spaces of hat A_alpha - lambda I and its transpose,
// as many vectors as the block has copies of lambda, bi-orthonormalised) and mapped back by (14),
// (26). [O(count b^3 + count n b)]
std::vector<EigenPair> eigenPairsByFourierBlocks(const Matrix& a, int n, const std::vector<TaggedEigenvalue>& spectrum,
                                                 size_t count);

// Largest |A v - lambda v| and |w^T A - lambda w^T| of a pair (0 for a pair without vectors). [O(size^2)]
double eigenPairResidual(const Matrix& a, const EigenPair& pair);

// Catmull-Clark's subdivision matrix on the 1-ring of a valence-n interior vertex surrounded by
// quads: rows and columns v, e_0..e_{n-1} (spoke ends), f_0..f_{n-1} (far corners of the quads),
// built from computeCatmullClarkPoints (OpenSubdiv's rules). [O(n^2)]
Matrix catmullClarkRingMatrix(int n);

// The same matrix in the block-circulant layout (13): column j holds (v, e_j, f_j), v listed in
// every column with its matrix column split evenly among the copies. [O(n^2)]
Matrix catmullClarkCirculantMatrix(int n);

// The matrix whose spectrum schemeSpectrum lists: (13) for RTS and BPS, catmullClarkRingMatrix for
// Catmull-Clark. Throws std::invalid_argument for C2PS. [O(n^2) refinements]
Matrix schemeMatrix(Scheme scheme, int n);

// The spectrum of `scheme` (RTS, BPS: matrix (13); Catmull-Clark: the 1-ring matrix, 2n + 1
// eigenvalues) at valence n by decreasing modulus, each tagged with its Fourier block. Throws
// std::invalid_argument for C2PS. [O(n^2)]
std::vector<TaggedEigenvalue> schemeSpectrum(Scheme scheme, int n);

// The eigenpairs of schemeSpectrum's first `count` eigenvalues, vectors in schemeMatrix's order
// (Catmull-Clark: v, e_j, f_j; the centre's left entry is the sum over its copies, so w^T v is
// unchanged). [O(n^2)]
std::vector<EigenPair> schemeEigenPairs(Scheme scheme, int n, size_t count);

// [SECTION] C2PS: Lemma 5 and (30), measured

// One C2PS step m applied to RTS's eigenvectors v_k (k < 6) of valence n, links 0..5 (C2PS makes
// links 0..5 of level m from those of level m - 1 alone; the valence is n 2^m).
struct C2psScalingStep {
  int m, valence;
  // Lemma 5: the eigencoefficients (26) p_h = w_h^T T^m v_k, with RTS's left eigenvectors at valence
  // n 2^m (Table 1's profiles hold at every valence), are lambda_k^m delta_hk: the largest error.
  double coefficientError;
  // (30): |T^m v_k - lambda_k^m v_k^[n 2^m]|, largest over k < 6, on links 0..5 (O(8^-m)) and on
  // links 0, 1 (zero).
  double deviation, deviationLinks01;
};

// One C2PS step (rules (1)-(5), (29)) keeping the grid's links 0..K: the step makes links
// 0..2K-1 from them, so these are exact. [O(n K)]
PolarGrid c2psStepOnLinks(const PolarGrid& grid);

// Steps 1..steps of the above (n >= 5, as RTS). [O(steps 6 n 2^steps) with C2PS's O(n) rules]
std::vector<C2psScalingStep> c2psEigencoefficientScaling(int n, int steps);

}  // namespace polarview
