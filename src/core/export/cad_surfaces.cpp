// The CAD writers' surfaces (cad_surfaces.h).
#include "core/export/cad_surfaces.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include <glm/common.hpp>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

bool isFinite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Values and first and second derivatives of the degree-p B-spline basis functions nonzero at t
// in knot span `span` (The NURBS Book, Piegl & Tiller, algorithm A2.3): ders[k][r], r = 0..p is
// the k-th derivative of N_{span-p+r}.
std::array<std::vector<double>, 3> basisDerivatives(const std::vector<double>& knots, int span, int p, double t) {
  std::vector<std::vector<double>> ndu(size_t(p + 1), std::vector<double>(size_t(p + 1)));
  std::vector<double> left(size_t(p + 1)), right(size_t(p + 1));
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[size_t(j)] = t - knots[size_t(span + 1 - j)];
    right[size_t(j)] = knots[size_t(span + j)] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[size_t(j)][size_t(r)] = right[size_t(r + 1)] + left[size_t(j - r)];  // lower triangle: knot differences
      const double temp = ndu[size_t(r)][size_t(j - 1)] / ndu[size_t(j)][size_t(r)];
      ndu[size_t(r)][size_t(j)] = saved + right[size_t(r + 1)] * temp;
      saved = left[size_t(j - r)] * temp;
    }
    ndu[size_t(j)][size_t(j)] = saved;
  }
  std::array<std::vector<double>, 3> ders;
  for (auto& row : ders) row.assign(size_t(p + 1), 0.0);
  for (int r = 0; r <= p; ++r) ders[0][size_t(r)] = ndu[size_t(r)][size_t(p)];
  // Derivatives from the differences of the lower-degree functions (A2.3's a-table).
  std::vector<std::vector<double>> a(2, std::vector<double>(size_t(p + 1)));
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= std::min(2, p); ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[size_t(s2)][0] = a[size_t(s1)][0] / ndu[size_t(pk + 1)][size_t(rk)];
        d = a[size_t(s2)][0] * ndu[size_t(rk)][size_t(pk)];
      }
      const int j1 = rk >= -1 ? 1 : -rk, j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[size_t(s2)][size_t(j)] = (a[size_t(s1)][size_t(j)] - a[size_t(s1)][size_t(j - 1)]) / ndu[size_t(pk + 1)][size_t(rk + j)];
        d += a[size_t(s2)][size_t(j)] * ndu[size_t(rk + j)][size_t(pk)];
      }
      if (r <= pk) {
        a[size_t(s2)][size_t(k)] = -a[size_t(s1)][size_t(k - 1)] / ndu[size_t(pk + 1)][size_t(r)];
        d += a[size_t(s2)][size_t(k)] * ndu[size_t(r)][size_t(pk)];
      }
      ders[size_t(k)][size_t(r)] = d;
      std::swap(s1, s2);
    }
  }
  for (int k = 1, factor = p; k <= 2; ++k, factor *= (p - k + 1))
    for (double& value : ders[size_t(k)]) value *= factor;
  return ders;
}

}  // namespace

std::vector<double> clampedBezierKnots(int degree) {
  std::vector<double> knots(size_t(2 * (degree + 1)), 0.0);
  for (int k = degree + 1; k < 2 * (degree + 1); ++k) knots[size_t(k)] = 1.0;
  return knots;
}

CadSurfaceDerivatives evaluateCadSurface(const CadSurface& surface, double u, double v) {
  // One span: the last index whose knot is 0, i.e. span = degree.
  const BezierPatch& b = surface.bezier;
  const auto nu = basisDerivatives(clampedBezierKnots(b.degU), b.degU, b.degU, u);
  const auto nv = basisDerivatives(clampedBezierKnots(b.degV), b.degV, b.degV, v);
  CadSurfaceDerivatives out;
  for (int i = 0; i <= b.degU; ++i)
    for (int j = 0; j <= b.degV; ++j) {
      const Point& p = b.cp[size_t((b.degV + 1) * i + j)];
      const size_t si = size_t(i), sj = size_t(j);
      out.position += nu[0][si] * nv[0][sj] * p;
      out.du += nu[1][si] * nv[0][sj] * p;
      out.dv += nu[0][si] * nv[1][sj] * p;
      out.duu += nu[2][si] * nv[0][sj] * p;
      out.duv += nu[1][si] * nv[1][sj] * p;
      out.dvv += nu[0][si] * nv[2][sj] * p;
    }
  return out;
}

CadSurfaceSet cadSurfaces(const PatchSet& set, const std::string& sourceName) {
  checkFinitePatches(set, sourceName);  // before anything is made

  CadSurfaceSet out;
  out.boxDiagonal = patchBoxDiagonal(set);
  out.surfaces.reserve(set.patches.size());
  for (size_t k = 0; k < set.patches.size(); ++k) {
    const Patch& patch = set.patches[k];
    CadSurface surface;
    surface.kind = patch.kind;
    surface.level = patch.level;
    surface.ring = patch.ring;
    surface.patch = k;
    if (patch.kind != PatchKind::PoleCap) {
      surface.bezier = bicubicBezier(patch);
      out.surfaces.push_back(std::move(surface));
      continue;
    }
    ++out.capSectors;
    double deviation = 0.0;
    std::vector<BezierPatch> pieces = fitPoleCap(patch, BezierViewOptions{}, out.boxDiagonal, &deviation);
    out.capMaxDeviation = std::max(out.capMaxDeviation, deviation);
    surface.pieces = int(pieces.size());
    for (size_t piece = 0; piece < pieces.size(); ++piece) {
      surface.piece = int(piece);
      surface.bezier = std::move(pieces[piece]);
      out.surfaces.push_back(surface);
    }
  }
  // Counts and box of what is written; a point that overflowed in the conversion is refused too.
  out.boxMin = Point(0.0);
  out.boxMax = Point(0.0);
  bool first = true;
  for (const CadSurface& surface : out.surfaces) {
    ++out.written[size_t(surface.kind)];
    for (const Point& p : surface.bezier.cp) {
      if (!isFinite(p)) throw InputError(sourceName, 0, "a B-spline control point overflowed (the coordinates are too large)");
      out.boxMin = first ? p : glm::min(out.boxMin, p);
      out.boxMax = first ? p : glm::max(out.boxMax, p);
      first = false;
    }
  }
  return out;
}

std::string shortestDouble(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

std::string cadReal(double value, char exponentLetter) {
  const std::string text = shortestDouble(value);
  const size_t exponent = text.find('e');
  const std::string mantissa = text.substr(0, exponent);
  std::string out = mantissa.find('.') == std::string::npos ? mantissa + "." : mantissa;
  if (exponent != std::string::npos) out += exponentLetter + text.substr(exponent + 1);
  return out;
}

}  // namespace polarview
