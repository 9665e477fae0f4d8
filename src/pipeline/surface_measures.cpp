#include "pipeline/surface_measures.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/mesh/constants.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/topology.h"

namespace polarview {
namespace {

// Gauss-Legendre nodes and weights on [0, 1] (Newton's iteration on P_n from Chebyshev guesses).
struct QuadratureRule {
  std::vector<double> nodes, weights;
};
QuadratureRule gaussLegendre(int n) {
  QuadratureRule rule;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;  // P_0, P_1, then up to P_n by Bonnet's recursion
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.nodes.push_back(0.5 * (1.0 - x));
    rule.weights.push_back(1.0 / ((1.0 - x * x) * derivative * derivative));  // 2 / (...) on [-1, 1], halved
  }
  return rule;
}

// The surface integrals the measures come from, relative to a reference point o.
struct Moments {
  double area = 0.0, volume = 0.0;
  Point shellFirst{0.0}, solidFirst{0.0};        // ∫ x dA, ∫_V x dV
  glm::dmat3 shellSecond{0.0}, solidSecond{0.0};  // ∫ x x^T dA, ∫_V x x^T dV
};

void accumulate(Moments& m, const Point& x, const Point& n, double w) {
  const double dA = glm::length(n) * w;
  m.area += dA;
  m.volume += glm::dot(x, n) * w / 3.0;
  m.shellFirst += x * dA;
  for (int i = 0; i < 3; ++i) {
    m.solidFirst[i] += 0.5 * x[i] * x[i] * n[i] * w;  // F = x_i^2 / 2 e_i
    for (int j = 0; j < 3; ++j) {
      m.shellSecond[i][j] += x[i] * x[j] * dA;
      // F = x_i^3 / 3 e_i on the diagonal, x_i^2 x_j / 2 e_i off it
      m.solidSecond[i][j] += (i == j ? x[i] * x[i] * x[i] / 3.0 : 0.5 * x[i] * x[i] * x[j]) * n[i] * w;
    }
  }
}

Moments integrate(const std::vector<Patch>& patches, const Point& o, int points) {
  const QuadratureRule rule = gaussLegendre(points);
  Moments m;
  for (const Patch& patch : patches)
    for (int a = 0; a < points; ++a)
      for (int b = 0; b < points; ++b) {
        const SurfacePoint s = evaluatePatch(patch, rule.nodes[size_t(a)], rule.nodes[size_t(b)]);
        accumulate(m, s.position - o, glm::cross(s.du, s.dv), rule.weights[size_t(a)] * rule.weights[size_t(b)]);
      }
  return m;
}

// The inertia tensor about the centroid of a body of `mass` whose second moment about o is
// `second` and whose centroid is `centre` (relative to o): tr(C) I - C, C the central moment.
glm::dmat3 centralInertia(const glm::dmat3& second, double mass, const Point& centre) {
  glm::dmat3 central = second;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) central[i][j] -= mass * centre[i] * centre[j];
  const double trace = central[0][0] + central[1][1] + central[2][2];
  const glm::dmat3 inertia = glm::dmat3(trace) - central;
  return 0.5 * (inertia + glm::transpose(inertia));  // symmetric: the two divergence forms round apart
}

}  // namespace

SurfaceMeasures measureSurface(const std::vector<Patch>& patches, bool closed, int points) {
  points = std::clamp(points, 2, 16);
  SurfaceMeasures r;
  r.patches = patches.size();
  r.points = points;
  r.closed = closed;
  if (patches.empty()) return r;
  // Relative to the patches' mean centre: the volume's and moments' terms stay the model's size.
  Point o(0.0);
  for (const Patch& patch : patches) o += evaluatePatch(patch, 0.5, 0.5).position / double(patches.size());
  const Moments m = integrate(patches, o, points), coarse = integrate(patches, o, std::max(points / 2, 1));
  r.area = m.area;
  r.areaError = std::abs(m.area - coarse.area);
  if (m.area > 0.0) {
    const Point c = m.shellFirst / m.area;
    r.areaCentroid = o + c;
    r.shellInertia = centralInertia(m.shellSecond, m.area, c);
  }
  if (!closed || m.volume == 0.0) return r;
  r.volume = m.volume;
  r.volumeError = std::abs(m.volume - coarse.volume);
  const Point c = m.solidFirst / m.volume;
  r.centroid = o + c;
  r.inertia = centralInertia(m.solidSecond, m.volume, c);
  return r;
}

bool meshIsClosed(const PolyMesh& mesh, const MeshTopology& topology) {
  if (!mesh.tags.holes.empty() || mesh.faceCount() == 0) return false;
  for (Index e = 0; e < topology.edgeCount; ++e)
    if (topology.edgeOnBoundary(e)) return false;
  return true;
}

bool meshIsClosed(const PolyMesh& mesh) {
  ManifoldSplit split;  // a non-manifold mesh is measured as it is refined: its split
  MeshTopology topology;
  refinableMesh(mesh, split, topology, "<mesh>");
  return meshIsClosed(mesh, topology);
}

}  // namespace polarview
