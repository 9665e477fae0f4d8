// Spectra of subdivision matrices (spectrum.h).
#include "core/subdiv/spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/mesh/topology.h"
#include "core/subdiv/bps.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/rts.h"

namespace polarview {
namespace {
constexpr double kSpectrumPi = 3.14159265358979323846264338327950288;
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
  ComplexMatrix block(6, std::vector<Complex>(6, 0.0));
  for (int h = 0; h < n; ++h) {
    Complex omega = std::polar(1.0, 2.0 * kSpectrumPi * double((long long)h * alpha % n) / n);
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) block[r][c] += omega * a[polarMatrixIndex(r, 0)][polarMatrixIndex(c, h)];
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

std::vector<TaggedEigenvalue> spectrumByFourierBlocks(const Matrix& a, int n) {
  std::vector<TaggedEigenvalue> all;
  for (int alpha = 0; alpha < n; ++alpha)
    for (Complex z : eigenvalues(fourierBlock(a, n, alpha))) all.push_back({z, alpha});
  std::stable_sort(all.begin(), all.end(),
                   [](const TaggedEigenvalue& x, const TaggedEigenvalue& y) { return std::abs(x.value) > std::abs(y.value); });
  return all;
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

std::vector<TaggedEigenvalue> schemeSpectrum(Scheme scheme, int n) {
  std::vector<TaggedEigenvalue> all;
  const SchemeTraits& traits = schemeTraits(scheme);
  if (!traits.polar()) {
    const Matrix a = catmullClarkRingMatrix(n);
    ComplexMatrix dense(a.size(), std::vector<Complex>(a.size()));
    for (size_t r = 0; r < a.size(); ++r)
      for (size_t c = 0; c < a.size(); ++c) dense[r][c] = a[r][c];
    for (Complex z : eigenvalues(dense)) all.push_back({z, -1});
    std::stable_sort(all.begin(), all.end(),
                     [](const TaggedEigenvalue& x, const TaggedEigenvalue& y) { return std::abs(x.value) > std::abs(y.value); });
    return all;
  }
  if (traits.keepsValence)
    return spectrumByFourierBlocks(polarSubdivisionMatrix(n, [&](const PolarGrid& g) { return traits.refineGrid(g, false); }), n);
  throw std::invalid_argument("schemeSpectrum: C2PS doubles the valence, it has no stationary matrix (use rts)");
}

}  // namespace polarview
