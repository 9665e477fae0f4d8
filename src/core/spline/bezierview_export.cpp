// BezierView (.bv) export of a PatchSet: exact bicubic Bezier patches for the B-spline patches,
// interpolating (5, d) Bezier patches for the pole caps (rules and accuracy in the header).
#include "core/spline/bezierview_export.h"

#include "core/mesh/constants.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <istream>
#include <map>
#include <ostream>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

// |v| without squaring's underflow (std::hypot): a cap of a 1e-150 model deviates by ~1e-163, whose
// square is below double's range.
double vectorLength(const Point& v) { return std::hypot(v.x, v.y, v.z); }


constexpr int kCapRadialDegree = 5;  // the cap is a quintic in u (header)

bool isFinite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Bernstein polynomial B_j^d(t), with integer powers so that B_j^d(0) and B_j^d(1) are exactly 0 or 1.
double bernstein(int d, int j, double t) {
  double binomial = 1.0;
  for (int k = 1; k <= j; ++k) binomial = binomial * double(d - j + k) / double(k);
  double value = binomial;
  for (int k = 0; k < j; ++k) value *= t;
  for (int k = 0; k < d - j; ++k) value *= 1.0 - t;
  return value;
}

// Inverse of the collocation matrix A[m][j] = B_j^d(nodes[m]) by Gauss-Jordan with partial
// pivoting, row-major. A row of A that is a unit vector (a node at 0 or 1) gives the same unit row
// in the inverse exactly, so the interpolant's end coefficients are the end samples bit for bit.
std::vector<double> collocationInverse(const std::vector<double>& nodes, int d) {
  const int n = d + 1;
  std::vector<double> a(size_t(n) * n), inv(size_t(n) * n, 0.0);
  for (int m = 0; m < n; ++m) {
    for (int j = 0; j < n; ++j) a[size_t(m) * n + j] = bernstein(d, j, nodes[size_t(m)]);
    inv[size_t(m) * n + m] = 1.0;
  }
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(a[size_t(r) * n + col]) > std::abs(a[size_t(pivot) * n + col])) pivot = r;
    for (int k = 0; k < n; ++k) {
      std::swap(a[size_t(col) * n + k], a[size_t(pivot) * n + k]);
      std::swap(inv[size_t(col) * n + k], inv[size_t(pivot) * n + k]);
    }
    const double p = a[size_t(col) * n + col];
    for (int k = 0; k < n; ++k) {
      a[size_t(col) * n + k] /= p;
      inv[size_t(col) * n + k] /= p;
    }
    for (int r = 0; r < n; ++r) {
      const double f = a[size_t(r) * n + col];
      if (r == col || f == 0.0) continue;
      for (int k = 0; k < n; ++k) {
        a[size_t(r) * n + k] -= f * a[size_t(col) * n + k];
        inv[size_t(r) * n + k] -= f * inv[size_t(col) * n + k];
      }
    }
  }
  return inv;
}

// Chebyshev-Lobatto nodes on [0,1], ascending, the ends exactly 0 and 1.
std::vector<double> lobattoNodes(int d) {
  std::vector<double> t(size_t(d) + 1);
  for (int k = 0; k <= d; ++k) t[size_t(k)] = k == 0 ? 0.0 : k == d ? 1.0 : 0.5 * (1.0 - std::cos(kPi * k / d));
  return t;
}

// Parameter of sub-sector `piece` of `split` at local t in [0,1]; the shared ends of neighbouring
// sub-sectors come out as the same double.
double pieceParameter(int piece, int split, double t) {
  const double va = double(piece) / split, vb = double(piece + 1) / split;
  return (1.0 - t) * va + t * vb;
}

// Appends x with 17 significant digits (round-trips; obj_io writes the shortest such text instead).
void appendNumber(std::string& out, double x) {
  char number[64];
  const auto result = std::to_chars(number, number + sizeof number, x, std::chars_format::general, 17);
  out.append(number, result.ptr);
}

void appendPatch(std::string& out, const BezierPatch& patch) {
  out += "5\n";
  out += std::to_string(patch.degU) + " " + std::to_string(patch.degV) + "\n";
  for (const Point& p : patch.cp) {
    appendNumber(out, p.x);
    out += ' ';
    appendNumber(out, p.y);
    out += ' ';
    appendNumber(out, p.z);
    out += '\n';
  }
}

// The group name of a (kind, level) pair (one token: BezierView reads it with %s).
std::string groupName(PatchKind kind, int level) {
  if (kind == PatchKind::PolarRing) return "polar-ring-" + std::to_string(level);
  return std::string(patchKindName(kind)) + "-level-" + std::to_string(level);
}

}  // namespace

Point BezierPatch::evaluate(double u, double v) const {
  // de Casteljau along v in every row, then along u over the row values.
  std::vector<Point> rows(size_t(degU) + 1), work(size_t(std::max(degU, degV)) + 1);
  for (int i = 0; i <= degU; ++i) {
    for (int j = 0; j <= degV; ++j) work[size_t(j)] = cp[size_t(i) * (degV + 1) + j];
    for (int r = degV; r > 0; --r)
      for (int j = 0; j < r; ++j) work[size_t(j)] = (1.0 - v) * work[size_t(j)] + v * work[size_t(j) + 1];
    rows[size_t(i)] = work[0];
  }
  for (int r = degU; r > 0; --r)
    for (int i = 0; i < r; ++i) rows[size_t(i)] = (1.0 - u) * rows[size_t(i)] + u * rows[size_t(i) + 1];
  return rows[0];
}

size_t BezierViewStats::total() const {
  size_t sum = 0;
  for (size_t n : written) sum += n;
  return sum;
}

BezierPatch bicubicBezier(const Patch& patch) {
  // B-spline -> Bezier per direction (header), first along u within each row j, then along v.
  auto convert = [](const Point& d0, const Point& d1, const Point& d2, const Point& d3, Point b[4]) {
    b[0] = (d0 + 4.0 * d1 + d2) / 6.0;
    b[1] = (2.0 * d1 + d2) / 3.0;
    b[2] = (d1 + 2.0 * d2) / 3.0;
    b[3] = (d1 + 4.0 * d2 + d3) / 6.0;
  };
  Point alongU[4][4];  // [j][i]
  for (int j = 0; j < 4; ++j)
    convert(patch.cp[size_t(4 * j)], patch.cp[size_t(4 * j + 1)], patch.cp[size_t(4 * j + 2)],
            patch.cp[size_t(4 * j + 3)], alongU[j]);
  BezierPatch out;
  out.degU = out.degV = 3;
  out.cp.resize(16);
  for (int i = 0; i < 4; ++i) {
    Point column[4];
    convert(alongU[0][i], alongU[1][i], alongU[2][i], alongU[3][i], column);
    for (int j = 0; j < 4; ++j) out.cp[size_t(4 * i + j)] = patch.origin + column[j];  // row i (u), column j (v)
  }
  return out;
}

std::vector<BezierPatch> approximatePoleCap(const Patch& cap, int split, int angularDegree) {
  const int du = kCapRadialDegree, dv = std::clamp(angularDegree, 3, 12);
  split = std::max(split, 1);
  std::vector<double> uNodes(size_t(du) + 1);
  for (int m = 0; m <= du; ++m) uNodes[size_t(m)] = double(m) / du;
  const std::vector<double> vNodes = lobattoNodes(dv);
  const std::vector<double> uInverse = collocationInverse(uNodes, du), vInverse = collocationInverse(vNodes, dv);

  std::vector<BezierPatch> pieces(static_cast<size_t>(split));
  std::vector<Point> samples(size_t(du + 1) * (dv + 1)), alongU(size_t(du + 1) * (dv + 1));
  for (int piece = 0; piece < split; ++piece) {
    // Samples of the cap on the (u node) x (v node) grid of this sub-sector.
    for (int m = 0; m <= du; ++m)
      for (int k = 0; k <= dv; ++k)
        samples[size_t(m) * (dv + 1) + k] =
            evaluatePatch(cap, uNodes[size_t(m)], pieceParameter(piece, split, vNodes[size_t(k)])).position;
    // Interpolate along u (exact: a quintic), then along v.
    for (int i = 0; i <= du; ++i)
      for (int k = 0; k <= dv; ++k) {
        Point sum(0.0);
        for (int m = 0; m <= du; ++m) sum += uInverse[size_t(i) * (du + 1) + m] * samples[size_t(m) * (dv + 1) + k];
        alongU[size_t(i) * (dv + 1) + k] = sum;
      }
    BezierPatch& out = pieces[size_t(piece)];
    out.degU = du;
    out.degV = dv;
    out.cp.resize(size_t(du + 1) * (dv + 1));
    for (int i = 0; i <= du; ++i)
      for (int j = 0; j <= dv; ++j) {
        Point sum(0.0);
        for (int k = 0; k <= dv; ++k) sum += vInverse[size_t(j) * (dv + 1) + k] * alongU[size_t(i) * (dv + 1) + k];
        out.cp[size_t(i) * (dv + 1) + j] = sum;
      }
    // Row u = 0 is the pole itself (r = 0), not p0 times a partition of unity with round-off.
    for (int j = 0; j <= dv; ++j) out.cp[size_t(j)] = cap.origin + cap.cp[0];
  }
  return pieces;
}

double poleCapDeviation(const Patch& cap, const std::vector<BezierPatch>& pieces, int samplesU, int samplesV) {
  const int split = int(pieces.size());
  samplesU = std::max(samplesU, 2);
  samplesV = std::max(samplesV, 2);
  double worst = 0.0;
  for (int piece = 0; piece < split; ++piece)
    for (int a = 0; a < samplesU; ++a) {
      const double u = double(a) / (samplesU - 1);
      for (int b = 0; b < samplesV; ++b) {
        const double t = double(b) / (samplesV - 1);
        const Point exact = evaluatePatch(cap, u, pieceParameter(piece, split, t)).position;
        worst = std::max(worst, vectorLength(pieces[size_t(piece)].evaluate(u, t) - exact));
      }
    }
  return worst;
}

std::vector<BezierPatch> fitPoleCap(const Patch& cap, const BezierViewOptions& options, double boxDiagonal,
                                    double* deviation) {
  // The coarsest split (1, 2, 4, ...) whose measured deviation meets the tolerance.
  const double tolerance = options.capTolerance * boxDiagonal;
  const int angularDegree = std::clamp(options.capAngularDegree, 3, 12);
  std::vector<BezierPatch> pieces;
  double measured = 0.0;
  for (int split = 1;; split *= 2) {
    pieces = approximatePoleCap(cap, split, angularDegree);
    measured = poleCapDeviation(cap, pieces, 9, 4 * angularDegree + 1);
    if (measured <= tolerance || split * 2 > std::max(options.capMaxSplit, 1)) break;
  }
  if (deviation) *deviation = measured;
  return pieces;
}

double patchBoxDiagonal(const PatchSet& set) {
  Point lo(1e300), hi(-1e300);
  auto add = [&](const Point& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (const Patch& patch : set.patches)
    for (int k = 0; k < 16; ++k)
      if (isPositionPoint(patch.kind, k)) add(patch.origin + patch.cp[size_t(k)]);
  return set.patches.empty() ? 0.0 : vectorLength(hi - lo);
}

void checkFinitePatches(const PatchSet& set, const std::string& sourceName) {
  for (size_t k = 0; k < set.patches.size(); ++k)
    for (int c = 0; c < 18; ++c)
      if (!isFinite(c < 16 ? set.patches[k].cp[size_t(c)] : set.patches[k].capExtra[size_t(c - 16)]) ||
          !isFinite(set.patches[k].origin))
        throw InputError(sourceName, 0,
                         "patch " + std::to_string(k) + " (" + patchKindName(set.patches[k].kind) +
                             ") has a non-finite control point: the input's coordinates are too large, too small or degenerate");
}

BezierViewStats writeBezierView(std::ostream& out, const PatchSet& set, const BezierViewOptions& options,
                                const std::string& sourceName) {
  checkFinitePatches(set, sourceName);  // before anything is written

  BezierViewStats stats;
  stats.boxDiagonal = patchBoxDiagonal(set);

  // Groups: (kind, level) in that order, patches in extraction order within each.
  std::map<std::pair<int, int>, std::vector<size_t>> groups;
  for (size_t k = 0; k < set.patches.size(); ++k)
    groups[{int(set.patches[k].kind), int(set.patches[k].level)}].push_back(k);

  std::string buffer;
  constexpr size_t kFlushAt = 1 << 20;
  auto write = [&](const BezierPatch& patch) {
    for (const Point& p : patch.cp)
      if (!isFinite(p)) throw InputError(sourceName, 0, "a Bezier control point overflowed (the coordinates are too large)");
    appendPatch(buffer, patch);
    if (buffer.size() >= kFlushAt) {
      out.write(buffer.data(), std::streamsize(buffer.size()));
      buffer.clear();
    }
  };
  for (const auto& [key, members] : groups) {
    const PatchKind kind = PatchKind(key.first);
    buffer += "Group " + std::to_string(++stats.groups) + " " + groupName(kind, key.second) + "\n";
    for (size_t k : members) {
      const Patch& patch = set.patches[k];
      if (kind != PatchKind::PoleCap) {
        write(bicubicBezier(patch));
        ++stats.written[size_t(kind)];
        continue;
      }
      ++stats.capSectors;
      double deviation = 0.0;
      const std::vector<BezierPatch> pieces = fitPoleCap(patch, options, stats.boxDiagonal, &deviation);
      stats.maxCapSplit = std::max(stats.maxCapSplit, int(pieces.size()));
      stats.capMaxDeviation = std::max(stats.capMaxDeviation, deviation);
      for (const BezierPatch& piece : pieces) write(piece);
      stats.written[size_t(kind)] += pieces.size();
    }
  }
  out.write(buffer.data(), std::streamsize(buffer.size()));
  out.flush();
  if (!out) throw InputError(sourceName, 0, "writing the .bv output failed");
  return stats;
}

std::vector<BezierViewGroup> readBezierView(std::istream& in, const std::string& sourceName) {
  std::vector<BezierViewGroup> groups;
  std::string token;
  auto fail = [&](const std::string& what) -> void { throw InputError(sourceName, 0, what); };
  while (in >> token) {
    if (token == "Group" || token == "group") {
      BezierViewGroup group;
      if (!(in >> group.id >> group.name)) fail("a Group line needs an id and a name");
      std::string rest;
      std::getline(in, rest);
      groups.push_back(std::move(group));
      continue;
    }
    int kind = 0;
    const auto parsed = std::from_chars(token.data(), token.data() + token.size(), kind);
    if (parsed.ec != std::errc() || parsed.ptr != token.data() + token.size())
      fail("expected a patch kind or a Group line, got '" + token + "'");
    if (kind != 4 && kind != 5) fail("patch kind " + token + " is not read here (only 4 and 5)");
    BezierPatch patch;
    if (!(in >> patch.degU)) fail("truncated patch header");
    if (kind == 5 && !(in >> patch.degV)) fail("truncated patch header");
    if (kind == 4) patch.degV = patch.degU;
    if (patch.degU < 1 || patch.degV < 1 || patch.degU > 64 || patch.degV > 64) fail("patch degree out of range");
    patch.cp.resize(size_t(patch.degU + 1) * (patch.degV + 1));
    for (Point& p : patch.cp)
      if (!(in >> p.x >> p.y >> p.z)) fail("truncated patch: fewer than (deg_u + 1)(deg_v + 1) points");
    if (groups.empty()) groups.emplace_back();
    groups.back().patches.push_back(std::move(patch));
  }
  return groups;
}

}  // namespace polarview
