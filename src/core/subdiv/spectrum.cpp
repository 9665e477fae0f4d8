// Spectra of subdivision matrices (spectrum.h).
#include "core/subdiv/spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/mesh/constants.h"
#include "core/mesh/topology.h"
#include "core/subdiv/bps.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/rts.h"

namespace polarview {
namespace {
// omega^k, omega = exp(2 pi i / n), with k reduced mod n first so large k lose no accuracy.
Complex unitRoot(int n, long long k) { return std::polar(1.0, 2.0 * kPi * double(((k % n) + n) % n) / n); }

int blockSize(const Matrix& a, int n) {
  if (n <= 0 || a.empty() || a.size() % size_t(n) != 0)
    throw std::invalid_argument("spectrum: matrix size is not a multiple of the valence");
  return int(a.size() / size_t(n));
}
}  // namespace

Matrix polarSubdivisionMatrix(int n, const std::function<PolarGrid(const PolarGrid&)>& refine) {
  Matrix a(6 * n, std::vector<double>(6 * n, 0.0));
  for (int h = 0; h < n; ++h)
    for (int c = 0; c < 6; ++c) {
      PolarGrid unit(n, 5);
      double share = 1.0;
      if (c == 0) {
        unit.pole = Point(1.0);
        share = 1.0 / n;
      } else {
        unit.q(c, h) = Point(1.0);
      }
      PolarGrid fine = refine(unit);
      for (int j = 0; j < n; ++j) {
        a[polarMatrixIndex(0, j)][polarMatrixIndex(c, h)] = share * fine.pole.x;
        for (int i = 1; i < 6; ++i) a[polarMatrixIndex(i, j)][polarMatrixIndex(c, h)] = share * fine.q(i, j).x;
      }
    }
  return a;
}

ComplexMatrix fourierBlock(const Matrix& a, int n, int alpha) {
  const int b = blockSize(a, n);
  ComplexMatrix block(size_t(b), std::vector<Complex>(size_t(b), 0.0));
  for (int h = 0; h < n; ++h) {
    const Complex omega = unitRoot(n, (long long)h * alpha);
    for (int r = 0; r < b; ++r)
      for (int c = 0; c < b; ++c) block[size_t(r)][size_t(c)] += omega * a[size_t(r)][size_t(b * h + c)];
  }
  return block;
}

std::vector<Complex> eigenvalues(ComplexMatrix h) {
  const int size = int(h.size());
  double norm = 0.0;
  for (auto& row : h)
    for (auto& x : row) norm = std::max(norm, std::abs(x));
  // Hessenberg reduction.
  for (int k = 0; k + 2 < size; ++k) {
    std::vector<Complex> v(size, 0.0);
    double alpha = 0.0;
    for (int i = k + 1; i < size; ++i) alpha += std::norm(h[i][k]);
    alpha = std::sqrt(alpha);
    if (alpha == 0.0) continue;
    Complex phase = std::abs(h[k + 1][k]) > 0.0 ? h[k + 1][k] / std::abs(h[k + 1][k]) : Complex(1.0);
    for (int i = k + 1; i < size; ++i) v[i] = h[i][k];
    v[k + 1] += phase * alpha;
    double vv = 0.0;
    for (int i = k + 1; i < size; ++i) vv += std::norm(v[i]);
    if (vv == 0.0) continue;
    // H <- (I - 2 v v*/v*v) H (I - 2 v v*/v*v)
    for (int c = 0; c < size; ++c) {
      Complex s = 0.0;
      for (int i = k + 1; i < size; ++i) s += std::conj(v[i]) * h[i][c];
      s *= 2.0 / vv;
      for (int i = k + 1; i < size; ++i) h[i][c] -= v[i] * s;
    }
    for (int r = 0; r < size; ++r) {
      Complex s = 0.0;
      for (int i = k + 1; i < size; ++i) s += h[r][i] * v[i];
      s *= 2.0 / vv;
      for (int i = k + 1; i < size; ++i) h[r][i] -= s * std::conj(v[i]);
    }
  }
  // Shifted QR on the active leading block 0..m-1.
  std::vector<Complex> result;
  const double eps = 1e-15;
  int m = size, iterations = 0;
  while (m > 0) {
    if (m == 1) {
      result.push_back(h[0][0]);
      break;
    }
    double sub = std::abs(h[m - 1][m - 2]);
    if (sub <= eps * (std::abs(h[m - 1][m - 1]) + std::abs(h[m - 2][m - 2])) || sub <= eps * norm * 1e-3) {
      result.push_back(h[m - 1][m - 1]);
      --m;
      iterations = 0;
      continue;
    }
    if (++iterations > 1000) throw std::runtime_error("eigenvalues: QR did not converge");
    // Wilkinson shift from the trailing 2x2 block (an exceptional shift now and then).
    Complex a = h[m - 2][m - 2], b = h[m - 2][m - 1], c = h[m - 1][m - 2], d = h[m - 1][m - 1];
    Complex tr = a + d, det = a * d - b * c;
    Complex root = std::sqrt(tr * tr / 4.0 - det);
    Complex mu1 = tr / 2.0 + root, mu2 = tr / 2.0 - root;
    Complex shift = std::abs(mu1 - d) < std::abs(mu2 - d) ? mu1 : mu2;
    if (iterations % 11 == 10) shift = d + Complex(0.75 * sub, 0.25 * sub);
    for (int i = 0; i < m; ++i) h[i][i] -= shift;
    std::vector<Complex> cs(m), sn(m);
    for (int k = 0; k + 1 < m; ++k) {  // H = Q R by Givens rotations
      Complex x = h[k][k], y = h[k + 1][k];
      double r = std::sqrt(std::norm(x) + std::norm(y));
      if (r == 0.0) {
        cs[k] = 1.0;
        sn[k] = 0.0;
        continue;
      }
      cs[k] = x / r;
      sn[k] = y / r;
      for (int col = k; col < m; ++col) {
        Complex top = h[k][col], bottom = h[k + 1][col];
        h[k][col] = std::conj(cs[k]) * top + std::conj(sn[k]) * bottom;
        h[k + 1][col] = -sn[k] * top + cs[k] * bottom;
      }
    }
    for (int k = 0; k + 1 < m; ++k) {  // H = R Q
      for (int row = 0; row <= std::min(k + 1, m - 1); ++row) {
        Complex left = h[row][k], right = h[row][k + 1];
        h[row][k] = left * cs[k] + right * sn[k];
        h[row][k + 1] = -left * std::conj(sn[k]) + right * std::conj(cs[k]);
      }
    }
    for (int i = 0; i < m; ++i) h[i][i] += shift;
  }
  return result;
}

std::vector<TaggedEigenvalue> spectrumByFourierBlocks(const Matrix& a, int n, bool centreOnce) {
  std::vector<TaggedEigenvalue> all;
  for (int alpha = 0; alpha < n; ++alpha) {
    ComplexMatrix block = fourierBlock(a, n, alpha);
    if (centreOnce && alpha != 0) {  // the centre's row and column are zero here: drop them
      block.erase(block.begin());
      for (auto& row : block) row.erase(row.begin());
    }
    for (Complex z : eigenvalues(block)) all.push_back({z, alpha});
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const TaggedEigenvalue& x, const TaggedEigenvalue& y) { return std::abs(x.value) > std::abs(y.value); });
  // Moduli equal up to round-off (a cos/sin pair's two blocks, Table 1's 1/4 in blocks 0, 2, n-2)
  // come in block order, each pair alpha, n - alpha together, whatever their last bits.
  auto pairOrder = [n](const TaggedEigenvalue& x, const TaggedEigenvalue& y) {
    const int px = std::min(x.alpha, n - x.alpha), py = std::min(y.alpha, n - y.alpha);
    return px != py ? px < py : x.alpha < y.alpha;
  };
  for (size_t first = 0, last = 0; first < all.size(); first = last) {
    for (last = first + 1; last < all.size(); ++last)
      if (std::abs(all[last - 1].value) - std::abs(all[last].value) > 1e-9 * std::abs(all[first].value)) break;
    std::stable_sort(all.begin() + long(first), all.begin() + long(last), pairOrder);
  }
  return all;
}

// [SECTION] Eigenvectors

namespace {

using ComplexVector = std::vector<Complex>;

double maxModulus(const ComplexVector& v) {
  double m = 0.0;
  for (const Complex& x : v) m = std::max(m, std::abs(x));
  return m;
}

// m vectors spanning the null space of the square matrix `b`, which has (numerically) rank
// size - m: Gaussian elimination with complete pivoting for size - m steps, the trailing block taken
// as zero, then back substitution for each free unknown.
std::vector<ComplexVector> nullVectors(ComplexMatrix b, int m) {
  const int size = int(b.size()), rank = size - m;
  std::vector<int> column(static_cast<size_t>(size));
  for (int c = 0; c < size; ++c) column[size_t(c)] = c;
  for (int k = 0; k < rank; ++k) {
    int pr = k, pc = k;
    for (int r = k; r < size; ++r)
      for (int c = k; c < size; ++c)
        if (std::abs(b[size_t(r)][size_t(c)]) > std::abs(b[size_t(pr)][size_t(pc)])) pr = r, pc = c;
    std::swap(b[size_t(k)], b[size_t(pr)]);
    for (auto& row : b) std::swap(row[size_t(k)], row[size_t(pc)]);
    std::swap(column[size_t(k)], column[size_t(pc)]);
    if (b[size_t(k)][size_t(k)] == 0.0) continue;  // rank deficient beyond m: a free unknown more
    for (int r = k + 1; r < size; ++r) {
      const Complex f = b[size_t(r)][size_t(k)] / b[size_t(k)][size_t(k)];
      for (int c = k; c < size; ++c) b[size_t(r)][size_t(c)] -= f * b[size_t(k)][size_t(c)];
    }
  }
  std::vector<ComplexVector> result;
  for (int free = rank; free < size; ++free) {
    ComplexVector x(size_t(size), 0.0);  // in pivoted column order
    x[size_t(free)] = 1.0;
    for (int k = rank - 1; k >= 0; --k) {
      Complex s = 0.0;
      for (int c = k + 1; c < size; ++c) s += b[size_t(k)][size_t(c)] * x[size_t(c)];
      x[size_t(k)] = b[size_t(k)][size_t(k)] == 0.0 ? 0.0 : -s / b[size_t(k)][size_t(k)];
    }
    ComplexVector v(static_cast<size_t>(size));
    for (int c = 0; c < size; ++c) v[size_t(column[size_t(c)])] = x[size_t(c)];
    result.push_back(v);
  }
  return result;
}

// The inverse of a small complex matrix by Gauss-Jordan with partial pivoting; false when a pivot
// is below `tiny` (singular: the eigenvalue is defective).
bool invert(ComplexMatrix m, ComplexMatrix* inverse, double tiny) {
  const size_t size = m.size();
  *inverse = ComplexMatrix(size, ComplexVector(size, 0.0));
  for (size_t i = 0; i < size; ++i) (*inverse)[i][i] = 1.0;
  for (size_t k = 0; k < size; ++k) {
    size_t p = k;
    for (size_t r = k + 1; r < size; ++r)
      if (std::abs(m[r][k]) > std::abs(m[p][k])) p = r;
    if (std::abs(m[p][k]) < tiny) return false;
    std::swap(m[k], m[p]);
    std::swap((*inverse)[k], (*inverse)[p]);
    const Complex pivot = m[k][k];
    for (size_t c = 0; c < size; ++c) m[k][c] /= pivot, (*inverse)[k][c] /= pivot;
    for (size_t r = 0; r < size; ++r) {
      if (r == k) continue;
      const Complex f = m[r][k];
      for (size_t c = 0; c < size; ++c) m[r][c] -= f * m[k][c], (*inverse)[r][c] -= f * (*inverse)[k][c];
    }
  }
  return true;
}

// Right and left eigenvectors of `block` for the m-fold eigenvalue `lambda`: right ones scaled to
// largest modulus 1 (phase: below), left ones recombined so
// that w_k^T v_l = delta_kl. False when lambda is defective (W^T V singular).
bool blockEigenvectors(const ComplexMatrix& block, Complex lambda, int m, std::vector<ComplexVector>* right,
                       std::vector<ComplexVector>* left) {
  const size_t b = block.size();
  ComplexMatrix shifted = block, transposed(b, ComplexVector(b));
  for (size_t i = 0; i < b; ++i) shifted[i][i] -= lambda;
  for (size_t r = 0; r < b; ++r)
    for (size_t c = 0; c < b; ++c) transposed[c][r] = shifted[r][c];
  *right = nullVectors(shifted, m);
  *left = nullVectors(transposed, m);
  for (ComplexVector& v : *right) {
    // The phase of the first non-negligible entry (a real block's vectors become real; Catmull-
    // Clark's cos mode is then even about e_0), the sign of the largest (Table 1's signs).
    const double top = maxModulus(v);
    Complex phase = 1.0;
    for (const Complex& x : v)
      if (std::abs(x) > 1e-9 * top) {
        phase = x / std::abs(x);
        break;
      }
    size_t largest = 0;
    for (size_t i = 0; i < b; ++i)
      if (std::abs(v[i]) > std::abs(v[largest]) * (1.0 + 1e-12)) largest = i;
    if ((v[largest] / phase).real() < 0.0) phase = -phase;
    for (Complex& x : v) x /= phase * top;
  }
  // Bi-orthonormalise: M = W^T V, W <- W M^{-T} so that W^T V = I.
  ComplexMatrix gram(size_t(m), ComplexVector(size_t(m), 0.0)), inverse;
  double scale = 0.0;
  for (int k = 0; k < m; ++k) scale = std::max(scale, maxModulus((*left)[size_t(k)]));
  for (int k = 0; k < m; ++k)
    for (int l = 0; l < m; ++l)
      for (size_t i = 0; i < b; ++i) gram[size_t(k)][size_t(l)] += (*left)[size_t(k)][i] * (*right)[size_t(l)][i];
  if (!invert(gram, &inverse, 1e-8 * scale)) return false;
  std::vector<ComplexVector> w(size_t(m), ComplexVector(b, 0.0));
  for (int k = 0; k < m; ++k)  // w_k = sum_l W_l (M^{-1})_{kl}
    for (int l = 0; l < m; ++l)
      for (size_t i = 0; i < b; ++i) w[size_t(k)][i] += inverse[size_t(k)][size_t(l)] * (*left)[size_t(l)][i];
  *left = w;
  return true;
}

}  // namespace

const char* fourierModeName(FourierMode mode) {
  switch (mode) {
    case FourierMode::Single: return "single";
    case FourierMode::Cos: return "cos";
    case FourierMode::Sin: return "sin";
    case FourierMode::Complex: return "complex";
  }
  return "?";
}

std::vector<EigenPair> eigenPairsByFourierBlocks(const Matrix& a, int n, const std::vector<TaggedEigenvalue>& spectrum,
                                                 size_t count) {
  const int b = blockSize(a, n);
  const double top = spectrum.empty() ? 1.0 : std::abs(spectrum.front().value);
  auto same = [&](Complex x, Complex y) { return std::abs(x - y) <= 1e-9 * std::max(1.0, std::abs(y)); };
  std::vector<EigenPair> pairs;
  for (size_t k = 0; k < std::min(count, spectrum.size()); ++k) {
    const Complex lambda = spectrum[k].value;
    const int alpha = spectrum[k].alpha;
    const bool real = std::abs(lambda.imag()) <= 1e-12 * std::max(1.0, std::abs(lambda));
    // A real eigenvalue of block alpha > n/2 is also one of block n - alpha (A is real): both are
    // computed there and written as the real and imaginary parts (14) of that block's vector.
    const int source = real ? std::min(alpha, n - alpha) % n : alpha;
    const FourierMode mode = !real ? FourierMode::Complex
                             : (2 * alpha) % n == 0 ? FourierMode::Single
                             : alpha < n - alpha    ? FourierMode::Cos
                                                    : FourierMode::Sin;
    EigenPair pair{real ? Complex(lambda.real()) : lambda, alpha, mode, {}, {}, {}, {}};
    // The copies of lambda in this block (its multiplicity m) and which of them this entry is.
    int m = 0, rank = 0;
    for (size_t e = 0; e < spectrum.size(); ++e)
      if (spectrum[e].alpha == alpha && same(spectrum[e].value, lambda)) m += 1, rank += e < k;
    std::vector<ComplexVector> right, left;
    if (std::abs(lambda) > 1e-12 * top &&
        blockEigenvectors(fourierBlock(a, n, source), pair.value, m, &right, &left)) {
      pair.rightProfile = right[size_t(rank)];
      pair.leftProfile = left[size_t(rank)];
      // (14): v_ij = v^_i omega^{j alpha}; (26): w_ij = w^_i omega^{-j alpha} / n, so that
      // w^T v = w^^T v^ = 1. The real pair: v = Re, Im of that and w = 2 Re, -2 Im of w's (Fourier
      // orthogonality makes the cross terms vanish); w^ takes the 2, as Table 1's does.
      if (mode == FourierMode::Cos || mode == FourierMode::Sin)
        for (Complex& x : pair.leftProfile) x *= 2.0;
      pair.right.resize(a.size());
      pair.left.resize(a.size());
      for (int j = 0; j < n; ++j) {
        const Complex forward = unitRoot(n, (long long)j * source), backward = std::conj(forward) / double(n);
        for (int i = 0; i < b; ++i) {
          const Complex v = pair.rightProfile[size_t(i)] * forward, w = pair.leftProfile[size_t(i)] * backward;
          const size_t row = size_t(b * j + i);
          switch (mode) {
            case FourierMode::Cos: pair.right[row] = v.real(), pair.left[row] = w.real(); break;
            case FourierMode::Sin: pair.right[row] = v.imag(), pair.left[row] = -w.imag(); break;
            default: pair.right[row] = v, pair.left[row] = w;
          }
        }
      }
    }
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

double eigenPairResidual(const Matrix& a, const EigenPair& pair) {
  double worst = 0.0;
  if (pair.right.empty()) return worst;
  for (size_t r = 0; r < a.size(); ++r) {
    Complex av = -pair.value * pair.right[r], wa = -pair.value * pair.left[r];
    for (size_t c = 0; c < a.size(); ++c) av += a[r][c] * pair.right[c], wa += pair.left[c] * a[c][r];
    worst = std::max({worst, std::abs(av), std::abs(wa)});
  }
  return worst;
}

Matrix catmullClarkRingMatrix(int n) {
  if (n < 3) throw std::invalid_argument("catmullClarkRingMatrix: valence >= 3");
  // The 1-ring of a valence-n vertex: v (0), spoke ends e_j (1 + j), quads' far corners f_j
  // (1 + n + j), quad j = (v, e_j, f_j, e_{j+1}). The child 1-ring of v's vertex point is the vertex
  // point, the spokes' edge points and the quads' face points, all functions of this ring alone.
  PolyMesh fan;
  fan.points.assign(size_t(2 * n + 1), Point(0.0));
  for (int j = 0; j < n; ++j)
    fan.addFace({0, Index(1 + j), Index(1 + n + j), Index(1 + (j + 1) % n)});
  const MeshTopology topo = buildTopology(fan, "<ring>");
  // Child index of each ring position: vertex point, edge points of the spokes, face points.
  std::vector<Index> child(size_t(2 * n + 1));
  child[0] = ccVertexPoint(topo, 0);
  for (Index e = 0; e < topo.edgeCount; ++e) {
    const Index a = topo.edgeVerts[2 * e], b = topo.edgeVerts[2 * e + 1];
    if (a == 0 || b == 0) child[size_t(a == 0 ? b : a)] = ccEdgePoint(topo, e);
  }
  for (int j = 0; j < n; ++j) child[size_t(1 + n + j)] = ccFacePoint(topo, j);
  Matrix a(size_t(2 * n + 1), std::vector<double>(size_t(2 * n + 1), 0.0));
  std::vector<Point> refined(size_t(ccChildVertexCount(topo)));
  for (int column = 0; column <= 2 * n; ++column) {
    std::vector<Point> unit(size_t(2 * n + 1), Point(0.0));
    unit[size_t(column)] = Point(1.0);
    computeCatmullClarkPoints(topo, fan, unit.data(), refined.data(), 1);
    for (int row = 0; row <= 2 * n; ++row) a[size_t(row)][size_t(column)] = refined[size_t(child[size_t(row)])].x;
  }
  return a;
}

Matrix catmullClarkCirculantMatrix(int n) {
  const Matrix ring = catmullClarkRingMatrix(n);
  // Ring position of point i (0: v, 1: e_j, 2: f_j) of column j.
  auto ringIndex = [n](int i, int j) { return size_t(i == 0 ? 0 : i == 1 ? 1 + j : 1 + n + j); };
  Matrix a(size_t(3 * n), std::vector<double>(size_t(3 * n), 0.0));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 3; ++i)
      for (int h = 0; h < n; ++h)
        for (int c = 0; c < 3; ++c)
          a[size_t(3 * j + i)][size_t(3 * h + c)] = ring[ringIndex(i, j)][ringIndex(c, h)] / (c == 0 ? n : 1);
  return a;
}

namespace {

// The block-circulant form of a scheme's matrix; C2PS has none.
Matrix circulantMatrix(Scheme scheme, int n) {
  const SchemeTraits& traits = schemeTraits(scheme);
  if (!traits.polar()) return catmullClarkCirculantMatrix(n);
  if (traits.keepsValence)
    return polarSubdivisionMatrix(n, [&](const PolarGrid& g) { return traits.refineGrid(g, false); });
  throw std::invalid_argument("schemeSpectrum: C2PS doubles the valence, it has no stationary matrix (use rts)");
}

}  // namespace

Matrix schemeMatrix(Scheme scheme, int n) {
  return schemeTraits(scheme).polar() ? circulantMatrix(scheme, n) : catmullClarkRingMatrix(n);
}

std::vector<TaggedEigenvalue> schemeSpectrum(Scheme scheme, int n) {
  // Catmull-Clark's centre is listed once in its 1-ring matrix: no zero eigenvalues for the copies.
  return spectrumByFourierBlocks(circulantMatrix(scheme, n), n, !schemeTraits(scheme).polar());
}

std::vector<EigenPair> schemeEigenPairs(Scheme scheme, int n, size_t count) {
  const Matrix a = circulantMatrix(scheme, n);
  const bool ring = !schemeTraits(scheme).polar();
  std::vector<EigenPair> pairs = eigenPairsByFourierBlocks(a, n, spectrumByFourierBlocks(a, n, ring), count);
  if (!ring) return pairs;
  // Back to the 1-ring order v, e_j, f_j: v's copies are equal in v; w's copies add up.
  for (EigenPair& pair : pairs) {
    if (pair.right.empty()) continue;
    std::vector<Complex> right(size_t(2 * n + 1)), left(size_t(2 * n + 1), 0.0);
    right[0] = pair.right[0];
    for (int j = 0; j < n; ++j) {
      left[0] += pair.left[size_t(3 * j)];
      right[size_t(1 + j)] = pair.right[size_t(3 * j + 1)], left[size_t(1 + j)] = pair.left[size_t(3 * j + 1)];
      right[size_t(1 + n + j)] = pair.right[size_t(3 * j + 2)], left[size_t(1 + n + j)] = pair.left[size_t(3 * j + 2)];
    }
    pair.right = std::move(right);
    pair.left = std::move(left);
  }
  return pairs;
}

// [SECTION] C2PS: Lemma 5 and (30), measured

PolarGrid c2psStepOnLinks(const PolarGrid& grid) {
  const PolarGrid fine = schemeTraits(Scheme::C2PS).refineGrid(grid, false);
  PolarGrid kept(fine.n, grid.links);
  kept.pole = fine.pole;
  std::copy(fine.ring.begin(), fine.ring.begin() + long(kept.ring.size()), kept.ring.begin());
  return kept;
}

std::vector<C2psScalingStep> c2psEigencoefficientScaling(int n, int steps) {
  constexpr int kLinks = 5;
  const std::vector<EigenPair> pairs = schemeEigenPairs(Scheme::RTS, n, 6);
  // op_k(t) of (14) with t = j / valence, the column's Greville abscissa at any valence.
  auto op = [&](const EigenPair& p, double t) {
    const int frequency = std::min(p.alpha, n - p.alpha);
    if (p.mode == FourierMode::Single) return 1.0;
    return p.mode == FourierMode::Cos ? std::cos(2.0 * kPi * frequency * t) : std::sin(2.0 * kPi * frequency * t);
  };
  // v_k^[valence] at links 0..5 (its profile scales with the valence-independent op_k).
  auto eigenvector = [&](const EigenPair& p, int valence) {
    PolarGrid g(valence, kLinks);
    g.pole = Point(p.rightProfile[0].real() * op(p, 0.0));
    for (int i = 1; i <= kLinks; ++i)
      for (int j = 0; j < valence; ++j) g.q(i, j) = Point(p.rightProfile[size_t(i)].real() * op(p, double(j) / valence));
    return g;
  };
  std::vector<C2psScalingStep> result;
  std::vector<PolarGrid> grids;
  for (const EigenPair& p : pairs) grids.push_back(eigenvector(p, n));
  for (int m = 1; m <= steps; ++m) {
    C2psScalingStep step{m, n << m, 0.0, 0.0, 0.0};
    for (size_t k = 0; k < pairs.size(); ++k) {
      PolarGrid& g = grids[k];
      g = c2psStepOnLinks(g);
      const double scale = std::pow(pairs[k].value.real(), m);  // lambda_k^m
      // (26): p_h = sum_ij (1/n) w^_h,i op_h(j/n) q_ij, the pole counted once per column.
      for (size_t h = 0; h < pairs.size(); ++h) {
        double coefficient = 0.0;
        for (int j = 0; j < g.n; ++j) {
          const double column = op(pairs[h], double(j) / g.n) / g.n;
          coefficient += pairs[h].leftProfile[0].real() * column * g.pole.x;
          for (int i = 1; i <= kLinks; ++i) coefficient += pairs[h].leftProfile[size_t(i)].real() * column * g.q(i, j).x;
        }
        step.coefficientError = std::max(step.coefficientError, std::abs(coefficient - (h == k ? scale : 0.0)));
      }
      // (30): against lambda_k^m v_k at the new valence.
      const PolarGrid target = eigenvector(pairs[k], g.n);
      auto deviate = [&](int i, double d) {
        step.deviation = std::max(step.deviation, d);
        if (i <= 1) step.deviationLinks01 = std::max(step.deviationLinks01, d);
      };
      deviate(0, std::abs(g.pole.x - scale * target.pole.x));
      for (int i = 1; i <= kLinks; ++i)
        for (int j = 0; j < g.n; ++j) deviate(i, std::abs(g.q(i, j).x - scale * target.q(i, j).x));
    }
    result.push_back(step);
  }
  return result;
}

}  // namespace polarview
