// cad_reference: writes a model's STEP and IGES files through `polarview export`'s format rows and,
// beside them, what polarview itself says about the surfaces written, for tests/cli/cad_occt.sh to
// compare with OpenCASCADE's reading (tests/cad/occt_compare.py).
//
//   cad_reference IN.obj SCHEME LEVEL PREFIX [K]   -> PREFIX.step, PREFIX.igs, PREFIX.table
//
// PREFIX.table, one record a line, numbers with 17 significant digits:
//   box D  cap_deviation C  area A  max_abs_K K  max_abs_H H  samples K  surfaces N
//       D: bounding-box diagonal; C: largest cap fit deviation (absolute); A: the surface area by
//       8 x 8 Gauss-Legendre over evaluatePatch per patch (caps over their whole sector);
//       K, H: largest |K|, |H| of evaluatePatch on a 4 x 4 interior grid of every patch;
//       samples: K of the seam samples below (default 4).
//   S index kind level ring piece pieces x y z patch  one per written surface, in file order; x y z:
//       its point at (u, v) = (1/2, 1/2), by which the faces a reader gives are matched; patch:
//       its patch's index (a cap sector's pieces share it)
//   P index u v <written 18> <limit 18> K H         point samples: (u, v) of the written surface;
//       written: position, du, dv, duu, duv, dvv of the written B-spline (evaluateCadSurface, de Boor);
//       limit: the same by evaluatePatch (caps: at the sector's v, derivatives by the chain rule);
//       K, H by evaluatePatch.
//   M kind a sideA ua va b sideB ub vb              seam samples: (ua, va) on surface a and (ub, vb)
//       on surface b are one point of the seam of the given kind (continuity.h's kind names, and
//       cap-piece: two pieces of one cap sector). Each side is sampled where `polarview continuity
//       --samples K` samples its patch's side: at (k + 1/2) / K of the patch's parameter (a cap
//       piece's side along v at the sector's v that fall in the piece).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "core/export/cad_surfaces.h"
#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/subdiv/scheme.h"
#include "pipeline/patch_export.h"
#include "pipeline/surface_export.h"

using namespace polarview;

namespace {

// A side of a written surface: s = 0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0 (patch.h's edge order).
struct Side {
  size_t surface = 0;
  int side = 0;
  std::vector<Point> cp;  // its Bezier control points, in order of its parameter t
  Point lo{0.0}, hi{0.0};
};

Point sideParameter(int side, double t) {
  static const double table[4][4] = {{1, 0, 0, 0}, {0, 1, 1, 0}, {1, 0, 0, 1}, {0, 0, 1, 0}};  // (u = a t + b, v = c t + d)
  const double* row = table[side];
  return Point(row[0] * t + row[1], row[2] * t + row[3], 0.0);
}

Side makeSide(const CadSurface& surface, size_t index, int side) {
  const BezierPatch& b = surface.bezier;
  Side out{index, side, {}, Point(1e300), Point(-1e300)};
  const int count = (side % 2 == 0) ? b.degU + 1 : b.degV + 1;
  for (int k = 0; k < count; ++k) {
    const int i = side == 0 || side == 2 ? k : (side == 1 ? b.degU : 0);
    const int j = side == 1 || side == 3 ? k : (side == 0 ? 0 : b.degV);
    out.cp.push_back(b.cp[size_t((b.degV + 1) * i + j)]);
    out.lo = glm::min(out.lo, out.cp.back());
    out.hi = glm::max(out.hi, out.cp.back());
  }
  return out;
}

// Value and derivative of a Bezier curve by de Casteljau.
std::pair<Point, Point> curveAt(const std::vector<Point>& cp, double t) {
  std::vector<Point> p = cp;
  const size_t n = p.size() - 1;
  for (size_t r = 1; r < n; ++r)
    for (size_t k = 0; k + r <= n; ++k) p[k] = (1 - t) * p[k] + t * p[k + 1];
  return {(1 - t) * p[0] + t * p[1], double(n) * (p[1] - p[0])};
}

// The parameter of the point of `cp` nearest to `point` (Newton from five starts) and its distance.
std::pair<double, double> project(const std::vector<Point>& cp, const Point& point) {
  double bestT = 0.0, best = 1e300;
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    for (int step = 0; step < 30; ++step) {
      const auto [c, d] = curveAt(cp, t);
      const double dd = glm::dot(d, d);
      if (dd <= 0.0) break;
      t = std::clamp(t - glm::dot(c - point, d) / dd, 0.0, 1.0);
    }
    const double distance = glm::length(curveAt(cp, t).first - point);
    if (distance < best) best = distance, bestT = t;
  }
  return {bestT, best};
}

const char* seamKind(const CadSurface& surfaceA, const CadSurface& surfaceB) {
  if (surfaceA.patch == surfaceB.patch) return "cap-piece";  // not a seam of the limit surface
  const PatchKind a = surfaceA.kind, b = surfaceB.kind;
  auto is = [&](PatchKind x, PatchKind y) { return (a == x && b == y) || (a == y && b == x); };
  const bool regularA = a == PatchKind::Regular || a == PatchKind::Boundary;
  const bool regularB = b == PatchKind::Regular || b == PatchKind::Boundary;
  if (a == PatchKind::EndCap || b == PatchKind::EndCap) return "end-cap";
  if (regularA && regularB) return "regular";
  if (is(PatchKind::PolarRing, PatchKind::PolarRing)) return "ring-ring";
  if (is(PatchKind::PolarRing, PatchKind::PoleCap)) return "ring-cap";
  if (is(PatchKind::PoleCap, PatchKind::PoleCap)) return "cap-cap";
  return regularA || regularB ? (a == PatchKind::PoleCap || b == PatchKind::PoleCap ? "regular-cap" : "regular-ring") : "other";
}

void printPoint(FILE* out, const Point& p) { std::fprintf(out, " %.17g %.17g %.17g", p.x, p.y, p.z); }

// The parameters t at which a side of `surface` is sampled: (k + 1/2) / K of its patch's side
// (sides 1 and 3 of a cap piece run along v, the sector's v = (piece + t) / pieces).
std::vector<double> sideSamples(const CadSurface& surface, int side, int samples) {
  std::vector<double> t;
  const bool alongSectorV = side % 2 == 1 && surface.pieces > 1;
  for (int k = 0; k < samples; ++k) {
    const double patchT = (k + 0.5) / samples;
    const double local = alongSectorV ? patchT * surface.pieces - surface.piece : patchT;
    if (local >= 0.0 && local < 1.0) t.push_back(local);
  }
  return t;
}

// Seam samples: each side's points (sideSamples) projected onto the sides of other surfaces whose
// boxes hold them (a uniform grid of boxes).
void writeSeams(FILE* out, const CadSurfaceSet& set, int samples) {
  std::vector<Side> sides;
  for (size_t s = 0; s < set.surfaces.size(); ++s)
    for (int side = 0; side < 4; ++side)
      if (!(side == 3 && set.surfaces[s].collapsedAtU0())) sides.push_back(makeSide(set.surfaces[s], s, side));
  const double tolerance = 1e-6 * set.boxDiagonal;
  double cell = 0.0;
  for (const Side& side : sides) cell = std::max(cell, glm::length(side.hi - side.lo));
  cell = std::max(cell, 1e-300);
  auto key = [&](const Point& p) { return std::make_tuple(long(std::floor(p.x / cell)), long(std::floor(p.y / cell)), long(std::floor(p.z / cell))); };
  std::map<std::tuple<long, long, long>, std::vector<size_t>> grid;
  for (size_t k = 0; k < sides.size(); ++k) grid[key(0.5 * (sides[k].lo + sides[k].hi))].push_back(k);

  for (const Side& side : sides)
    for (double t : sideSamples(set.surfaces[side.surface], side.side, samples)) {
      const Point point = curveAt(side.cp, t).first;
      const auto [cx, cy, cz] = key(point);
      bool found = false;
      for (long dx = -1; dx <= 1 && !found; ++dx)
        for (long dy = -1; dy <= 1 && !found; ++dy)
          for (long dz = -1; dz <= 1 && !found; ++dz) {
            const auto cellSides = grid.find({cx + dx, cy + dy, cz + dz});
            if (cellSides == grid.end()) continue;
            for (size_t k : cellSides->second) {
              const Side& other = sides[k];
              if (other.surface == side.surface) continue;
              if (glm::any(glm::lessThan(point, other.lo - tolerance)) || glm::any(glm::greaterThan(point, other.hi + tolerance))) continue;
              const auto [otherT, distance] = project(other.cp, point);
              if (distance > tolerance) continue;
              const Point a = sideParameter(side.side, t), b = sideParameter(other.side, otherT);
              std::fprintf(out, "M %s %zu %d %.17g %.17g %zu %d %.17g %.17g\n",
                           seamKind(set.surfaces[side.surface], set.surfaces[other.surface]), side.surface,
                           side.side, a.x, a.y, other.surface, other.side, b.x, b.y);
              found = true;
              break;
            }
          }
    }
}

// evaluatePatch at a written surface's (u, v), derivatives per the written parameters.
SurfacePoint limitAt(const PatchSet& set, const CadSurface& surface, double u, double v) {
  SurfacePoint p = evaluatePatch(set.patches[surface.patch], u, sectorV(surface, v));
  const double scale = 1.0 / surface.pieces;  // d(sector v) / d(piece v)
  p.dv *= scale;
  p.duv *= scale;
  p.dvv *= scale * scale;
  return p;
}

// Area by 8 x 8 Gauss-Legendre per patch over evaluatePatch; largest |K|, |H| on a 4 x 4 grid.
void surfaceMeasures(const PatchSet& set, double* area, double* maxK, double* maxH) {
  static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  *area = *maxK = *maxH = 0.0;
  for (const Patch& patch : set.patches) {
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b) {
        const double u = 0.5 + 0.5 * (a < 4 ? -x[a] : x[a - 4]), v = 0.5 + 0.5 * (b < 4 ? -x[b] : x[b - 4]);
        const SurfacePoint p = evaluatePatch(patch, u, v);
        *area += 0.25 * w[a % 4] * w[b % 4] * glm::length(glm::cross(p.du, p.dv));
      }
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const SurfacePoint p = evaluatePatch(patch, (a + 0.5) / 4, (b + 0.5) / 4);
        *maxK = std::max(*maxK, std::abs(p.gaussian));
        *maxH = std::max(*maxH, std::abs(p.mean));
      }
  }
}

int run(int argc, char** argv) {
  if (argc != 5 && argc != 6) throw std::runtime_error("usage: cad_reference IN.obj SCHEME LEVEL PREFIX [K]");
  const int samples = argc == 6 ? std::stoi(argv[5]) : 4;
  if (samples < 1) throw std::runtime_error("K must be at least 1");
  const std::string input = argv[1], prefix = argv[4];
  const auto variant = parseSchemeVariant(argv[2]);
  if (!variant) throw std::runtime_error(std::string("unknown scheme ") + argv[2]);
  const int level = std::stoi(argv[3]);
  const PolyMesh mesh = loadObj(input);
  const PatchSet set = exportPatchSet(mesh, {variant->scheme, level, variant->uniformFirstStep}, input, false, size_t(1) << 26);

  ExportSettings settings;
  settings.source = input;
  settings.schemeLabel = schemeVariantLabel(*variant);
  settings.level = level;
  for (const char* format : {"step", "iges"})
    writeSurfaceFile(prefix + (format == std::string("step") ? ".step" : ".igs"), set, *exportFormatNamed(format), settings);

  const CadSurfaceSet surfaces = cadSurfaces(set, input);
  FILE* out = std::fopen((prefix + ".table").c_str(), "w");
  if (!out) throw std::runtime_error("cannot write " + prefix + ".table");
  double area = 0, maxK = 0, maxH = 0;
  surfaceMeasures(set, &area, &maxK, &maxH);
  std::fprintf(out, "box %.17g cap_deviation %.17g area %.17g max_abs_K %.17g max_abs_H %.17g samples %d surfaces %zu\n",
               surfaces.boxDiagonal, surfaces.capMaxDeviation, area, maxK, maxH, samples, surfaces.surfaces.size());
  for (size_t s = 0; s < surfaces.surfaces.size(); ++s) {
    const CadSurface& surface = surfaces.surfaces[s];
    std::fprintf(out, "S %zu %s %d %d %d %d", s, patchKindName(surface.kind), surface.level, surface.ring, surface.piece,
                 surface.pieces);
    printPoint(out, evaluateCadSurface(surface, 0.5, 0.5).position);
    std::fprintf(out, " %zu\n", surface.patch);
  }
  // Two point samples per surface at scattered interior parameters (a cap's u away from the pole).
  for (size_t s = 0; s < surfaces.surfaces.size(); ++s)
    for (int k = 0; k < 2; ++k) {
      const double u = 0.1 + 0.8 * std::fmod(0.5 + (2 * s + k) * 0.6180339887498949, 1.0);
      const double v = 0.05 + 0.9 * std::fmod(0.25 + (2 * s + k) * 0.7548776662466927, 1.0);
      const CadSurfaceDerivatives written = evaluateCadSurface(surfaces.surfaces[s], u, v);
      const SurfacePoint limit = limitAt(set, surfaces.surfaces[s], u, v);
      std::fprintf(out, "P %zu %.17g %.17g", s, u, v);
      for (const Point& p : {written.position, written.du, written.dv, written.duu, written.duv, written.dvv}) printPoint(out, p);
      for (const Point& p : {limit.position, limit.du, limit.dv, limit.duu, limit.duv, limit.dvv}) printPoint(out, p);
      std::fprintf(out, " %.17g %.17g\n", limit.gaussian, limit.mean);
    }
  writeSeams(out, surfaces, samples);
  if (std::fclose(out) != 0) throw std::runtime_error("cannot write " + prefix + ".table");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cad_reference: %s\n", e.what());
    return 1;
  }
}
