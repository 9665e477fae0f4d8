// Draw selection (see draw_selection.h and docs/shading.md, "Close-ups: detail per region").
#include "pipeline/draw_selection.h"

#include "core/subdiv/parallel_for.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace polarview {
namespace {

constexpr int kMaxSegments = 64;  // GL's (and patch.tesc's) largest tessellation level
// Neighbouring rows' group counts may differ by this much (a circle's density then fits both).
constexpr int kMaxGroupRatioLog2 = 5;

// Control point k of the patch turned upright (Patch::ringTurn: a ring patch's u outwards, v along
// its row; other kinds are not turned), in absolute coordinates.
Point absolutePoint(const Patch& patch, int k) {
  return patch.origin + patch.cp[size_t(turnedControlIndex(k, patch.ringTurn))];
}

// The limit point at a corner of a B-spline patch's square, over control point (i, j) (1 or 2):
// (1, 4, 1) x (1, 4, 1) / 36.
Point splineCorner(const Patch& patch, int i, int j) {
  static constexpr double kW[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6};
  Point sum(0.0);
  for (int b = -1; b <= 1; ++b)
    for (int a = -1; a <= 1; ++a) sum += (kW[a + 1] * kW[b + 1]) * absolutePoint(patch, 4 * (j + b) + (i + a));
  return sum;
}

// A cap's rim point at its sector's start and end: the boundary B-spline b_{j-1..j+2} at its knots.
Point capRimStart(const Patch& cap) {
  return (absolutePoint(cap, 6) + 4.0 * absolutePoint(cap, 7) + absolutePoint(cap, 8)) / 6.0;
}
Point capRimEnd(const Patch& cap) {
  return (absolutePoint(cap, 7) + 4.0 * absolutePoint(cap, 8) + absolutePoint(cap, 9)) / 6.0;
}

bool near(const Point& a, const Point& b, double scale) {
  return glm::length(a - b) <= 1e-7 * scale;
}

struct Frustum {
  std::array<glm::dvec4, 6> planes{};
  // Outside when the box's corner furthest along a plane's normal is behind it.
  bool outside(const glm::dvec3& lo, const glm::dvec3& hi) const {
    for (const glm::dvec4& plane : planes) {
      const glm::dvec3 corner(plane.x >= 0.0 ? hi.x : lo.x, plane.y >= 0.0 ? hi.y : lo.y, plane.z >= 0.0 ? hi.z : lo.z);
      if (glm::dot(glm::dvec3(plane), corner) + plane.w < 0.0) return true;
    }
    return false;
  }
};

// Gribb & Hartmann: the clip planes of clip = M world are row 3 +- rows 0..2 of M.
Frustum frustumOf(const glm::dmat4& m) {
  Frustum f;
  const auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  for (int axis = 0; axis < 3; ++axis) {
    f.planes[size_t(2 * axis)] = row(3) + row(axis);
    f.planes[size_t(2 * axis + 1)] = row(3) - row(axis);
  }
  return f;
}

// Pixels a length inside a box covers: perspective at the box's nearest point (the near plane's
// distance at the least), orthographic at the view's scale.
struct Projector {
  glm::dvec3 eye{0.0};
  double pixelsPerUnit = 1.0;  // at distance 1 (perspective) or everywhere (orthographic)
  double nearDepth = 0.0;
  bool perspective = true;
  double pixels(double length, const glm::dvec3& lo, const glm::dvec3& hi) const {
    if (!perspective) return length * pixelsPerUnit;
    const double distance = glm::length(eye - glm::clamp(eye, lo, hi));
    return length * pixelsPerUnit / std::max(distance, nearDepth);
  }
};

int segmentsFor(double pixels, const DrawSelectionSettings& settings) {
  const double segments = std::ceil(pixels / std::max(settings.tessPixels, 0.5));
  return int(std::clamp(segments, 1.0, double(std::clamp(settings.maxTessLevel, 1, kMaxSegments))));
}

uint32_t vertexBound(int levelU, int levelV) { return uint32_t(levelU + 2) * uint32_t(levelV + 2); }

// A group of a row: sectors index * 2^log2 .. (index + 1) * 2^log2 - 1 (pyramid[log2][index]).
struct Group {
  int log2 = 0;
  int32_t index = 0;
};

int log2Exact(int64_t value) {
  int e = 0;
  while ((int64_t(1) << e) < value) ++e;
  return e;
}

}  // namespace

void patchBounds(const Patch& patch, glm::dvec3* lo, glm::dvec3* hi) {
  *lo = Point(std::numeric_limits<double>::max());
  *hi = Point(-std::numeric_limits<double>::max());
  const auto take = [&](const Point& c) {
    *lo = glm::min(*lo, c);
    *hi = glm::max(*hi, c);
  };
  if (patch.kind == PatchKind::PoleCap) {
    for (int k : {0, 6, 7, 8, 9}) take(patch.cp[size_t(k)]);  // isPositionPoint's
  } else {
    for (const Point& c : patch.cp) take(c);
  }
  *lo += patch.origin;
  *hi += patch.origin;
  // A cap bulges off the hull of its pole and rim points (its Taylor terms over a wedge of radius
  // R: heights of about K R^2, a few percent of R where the rings are below a pixel): a tenth of its
  // size more. (Not more: a thick box around a wedge under the eye would hold the eye.)
  if (patch.kind == PatchKind::PoleCap) {
    const glm::dvec3 margin(0.1 * glm::length(*hi - *lo));
    *lo -= margin;
    *hi += margin;
  }
}

// A patch's box, and a row sector's arc and rim (see Box). [O(1)]
DrawSelection::Box DrawSelection::boxOf(const Patch& patch) {
  Box box;
  patchBounds(patch, &box.lo, &box.hi);
  box.rimLo = box.lo, box.rimHi = box.hi;
  if (patch.kind == PatchKind::PolarRing) {
    // Of the control points over the outer circle: a measure in pixels, not the curve's length.
    box.arc = glm::length(absolutePoint(patch, 10) - absolutePoint(patch, 6));
    box.innerArc = glm::length(absolutePoint(patch, 9) - absolutePoint(patch, 5));
  } else if (patch.kind == PatchKind::PoleCap) {
    box.arc = glm::length(absolutePoint(patch, 8) - absolutePoint(patch, 7));
    box.rimLo = glm::min(capRimStart(patch), capRimEnd(patch));
    box.rimHi = glm::max(capRimStart(patch), capRimEnd(patch));
  }
  return box;
}

void DrawSelection::build(const std::vector<Patch>& patches, const std::vector<uint32_t>& slotOfPatch) {
  rows_.clear();
  circles_.clear();
  rowSlots_.clear();
  loneBoxes_.clear();
  loneSlots_.clear();
  loneHasJump_.clear();
  patchCount_ = patches.size();
  // The boxes in one pass over the patches in memory order, split over the cores (a patch is 440
  // bytes: C2PS 12's 246k are 108 MB to read).
  std::vector<Box> boxes(patches.size());
  parallelRanges(Index(patches.size()), threadsFor(patches.size()), [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p) boxes[size_t(p)] = boxOf(patches[size_t(p)]);
  });
  std::map<std::tuple<int, int, int>, std::vector<size_t>> byRow;  // (pole, level, link) -> patches
  const auto addLone = [&](size_t p) {
    loneBoxes_.push_back(boxes[p]);
    loneSlots_.push_back(slotOfPatch[p]);
    const auto& jumps = patches[p].edgeLevelDelta;
    loneHasJump_.push_back(std::any_of(jumps.begin(), jumps.end(), [](int8_t d) { return d != 0; }));
  };
  std::vector<size_t>* lastRow = nullptr;
  std::tuple<int, int, int> lastKey;
  for (size_t p = 0; p < patches.size(); ++p) {
    const Patch& patch = patches[p];
    const bool inRow = (patch.kind == PatchKind::PolarRing || patch.kind == PatchKind::PoleCap) && patch.pole >= 0 &&
                       patch.sector >= 0 && patch.link >= 0;
    if (!inRow) {
      addLone(p);
      continue;
    }
    // Patches of a row mostly come one after another: the last row's entry first.
    const std::tuple<int, int, int> key{patch.pole, patch.ring, patch.link};
    if (!lastRow || lastKey != key) lastRow = &byRow[key], lastKey = key;
    lastRow->push_back(p);
  }
  std::vector<std::vector<size_t>> rowPatches;
  for (auto& [key, members] : byRow) {
    const int32_t size = int32_t(members.size());
    std::vector<size_t> bySector(members.size(), SIZE_MAX);
    bool complete = true;
    for (size_t p : members) {
      const int32_t s = patches[p].sector;
      if (s >= size || bySector[size_t(s)] != SIZE_MAX) complete = false;
      else bySector[size_t(s)] = p;
    }
    // Neighbouring sectors share their control columns (a cap: its rim points), so the groups'
    // shared radial edges are the same points on both sides: by construction of Patch::sector
    // (patch_extraction.cpp, setRingPlace), checked here at two sectors.
    const bool cap = std::get<2>(key) == 0;
    for (int32_t s : {0, size / 2}) {
      if (!complete) break;
      const Patch& a = patches[bySector[size_t(s)]];
      const Patch& b = patches[bySector[size_t((s + 1) % size)]];
      const double scale = glm::length(absolutePoint(a, cap ? 9 : 15) - absolutePoint(a, cap ? 6 : 0));
      complete = cap ? near(absolutePoint(a, 7), absolutePoint(b, 6), scale)
                     : near(absolutePoint(a, 4), absolutePoint(b, 0), scale) && near(absolutePoint(a, 7), absolutePoint(b, 3), scale);
    }
    if (!complete) {
      for (size_t p : members) addLone(p);
      continue;
    }
    Row row;
    row.pole = std::get<0>(key);
    row.level = std::get<1>(key);
    row.link = std::get<2>(key);
    row.isCap = cap;
    row.start = int32_t(rowSlots_.size());
    row.size = size;
    for (size_t p : bySector) rowSlots_.push_back(int32_t(slotOfPatch[p]));
    if (cap) {
      row.polePoint = absolutePoint(patches[bySector[0]], 0);
      row.rimRadius = glm::length(capRimStart(patches[bySector[0]]) - row.polePoint);
    }
    // Group sizes 2^a that divide the row and leave at least 4 groups (a quarter turn at most).
    while (size % (2 << row.maxGroupLog2) == 0 && (2 << row.maxGroupLog2) * 4 <= size) ++row.maxGroupLog2;
    row.pyramid.resize(size_t(row.maxGroupLog2) + 1);
    for (size_t a = 0; a < row.pyramid.size(); ++a) row.pyramid[a].reserve(size_t(size) >> a);
    for (size_t p : bySector) row.pyramid[0].push_back(boxes[p]);
    for (size_t a = 1; a < row.pyramid.size(); ++a)
      for (size_t g = 0; g < row.pyramid[a - 1].size(); g += 2) {
        const Box& b0 = row.pyramid[a - 1][g];
        const Box& b1 = row.pyramid[a - 1][g + 1];
        row.pyramid[a].push_back({glm::min(b0.lo, b1.lo), glm::max(b0.hi, b1.hi), b0.innerArc + b1.innerArc, b0.arc + b1.arc,
                                  glm::min(b0.rimLo, b1.rimLo), glm::max(b0.rimHi, b1.rimHi)});
      }
    rows_.push_back(std::move(row));
    rowPatches.push_back(std::move(bySector));
  }
  linkRows(patches, rowPatches);
}

// The circles between a pole's rows, outside in: level m's links 3 | 2 (same sectors), level m's
// link 2 | level m + 1's link 4 (its S or 2S sectors, C2PS doubling), the last level's link 2 | its
// caps. Each is checked where the two sides' sector starts meet.
void DrawSelection::linkRows(const std::vector<Patch>& patches, const std::vector<std::vector<size_t>>& rowPatches) {
  std::map<std::tuple<int, int, int>, int> rowOf;
  for (size_t r = 0; r < rows_.size(); ++r) rowOf[{rows_[r].pole, rows_[r].level, rows_[r].link}] = int(r);
  const auto find = [&](int pole, int level, int link) {
    const auto it = rowOf.find({pole, level, link});
    return it == rowOf.end() ? -1 : it->second;
  };
  // Whether the inner edge of `outside`'s sectors meets the outer edge of `inside`'s (a cap's rim):
  // the sector starts of two of its sectors are sector starts there. [O(sectors)]
  const auto meets = [&](int outside, int inside) {
    const Row& out = rows_[size_t(outside)];
    const Row& in = rows_[size_t(inside)];
    if (in.size != out.size && in.size != 2 * out.size) return false;
    const auto startInside = [&](int32_t s) {
      const Patch& b = patches[rowPatches[size_t(inside)][size_t(s)]];
      return in.isCap ? capRimStart(b) : splineCorner(b, 2, 1);
    };
    const int32_t ratio = in.size / out.size;
    for (int32_t s : {0, out.size / 2 + 1}) {
      const Patch& a = patches[rowPatches[size_t(outside)][size_t(s % out.size)]];
      const Point onOut = splineCorner(a, 1, 1);
      const double scale = glm::length(splineCorner(a, 2, 1) - onOut);
      // Where the numbering agrees, sector s is sector ratio s inside; else any sector may be.
      bool found = near(onOut, startInside((s * ratio) % in.size), scale);
      for (int32_t t = 0; t < in.size && !found; ++t) found = near(onOut, startInside(t), scale);
      if (!found) return false;
    }
    return true;
  };
  const auto link = [&](int outside, int inside) {
    if (outside < 0 || inside < 0 || !meets(outside, inside)) return;
    rows_[size_t(outside)].innerCircle = rows_[size_t(inside)].outerCircle = int(circles_.size());
    circles_.push_back({inside, outside});
  };
  for (size_t r = 0; r < rows_.size(); ++r) {
    const Row& row = rows_[r];
    if (row.link == 3) link(int(r), find(row.pole, row.level, 2));
    if (row.link == 2) {
      link(int(r), find(row.pole, row.level + 1, 3));
      link(int(r), find(row.pole, row.level, 0));
    }
  }
  // A row with an edge not shared with a grouped row keeps that edge's own rule: one sector each.
  for (Row& row : rows_)
    if (row.outerCircle < 0 || (row.innerCircle < 0 && !row.isCap)) row.maxGroupLog2 = 0;
}

// One frame's selection (select): the view's measures, the groups chosen per row, the items.
struct DrawSelection::Frame {
  const DrawSelection& selection;
  const ViewParams& view;
  const DrawSelectionSettings& settings;
  Frustum frustum;
  Projector projector;
  double groupPixels = 0.0;
  std::vector<std::vector<Group>> groups;                 // per row
  std::vector<std::array<std::vector<int>, 2>> exponents;  // [row][0 inner, 1 outer][group]: its circles' 2^e
  DrawSelectionStats counted;
  std::vector<DrawItem> items;

  // A group on a circle, in sectors of the circle's finer side (2^log2 * finer / its row's).
  struct OnCircle {
    int64_t start = 0, size = 0;
    int side = 0;      // 0 inside (the circle is the row's outer edge), 1 outside
    size_t group = 0;  // in groups[its row]
    int domain = 0;
  };

  Frame(const DrawSelection& s, const ViewParams& v, const DrawSelectionSettings& st)
      : selection(s), view(v), settings(st), frustum(frustumOf(v.proj * v.view)), groups(s.rows_.size()) {
    projector.eye = view.eye;
    projector.perspective = view.proj[2][3] < -0.5;
    projector.pixelsPerUnit = 0.5 * settings.viewportHeight * view.proj[1][1];
    projector.nearDepth = projector.perspective ? std::max(view.proj[3][2] / (view.proj[2][2] - 1.0), 0.0) : 0.0;
    groupPixels = settings.groupScale * std::max(settings.tessPixels, 0.5);
  }

  const Row& row(int r) const { return selection.rows_[size_t(r)]; }
  const Box& boxOf(int r, const Group& g) const { return row(r).pyramid[size_t(g.log2)][size_t(g.index)]; }
  double across(const Box& b) const { return projector.pixels(glm::length(b.hi - b.lo), b.lo, b.hi); }
  // A group's arc along its outer circle, in pixels at that circle's distance.
  double arc(const Box& b) const { return projector.pixels(b.arc, b.rimLo, b.rimHi); }
  // How wide a group is anywhere: a ring's arc (rows are thin radially); a cap's wedge, an angle
  // theta from its pole, at radius r and distance d(r) >= |e - r| (e the eye's distance from the
  // pole) is r theta / d(r) wide: the largest of that over its radii.
  double width(const Row& row, const Box& b) const {
    if (!row.isCap) return arc(b);
    const double theta = b.arc / std::max(row.rimRadius, 1e-300), e = glm::length(view.eye - row.polePoint);
    const double boxDistance = glm::length(view.eye - glm::clamp(view.eye, b.lo, b.hi));
    double widest = 0.0;
    for (double r : {row.rimRadius, std::min(e, row.rimRadius), 0.5 * row.rimRadius, 0.25 * row.rimRadius}) {
      const double d = std::max({std::abs(e - r), boxDistance, projector.nearDepth});
      widest = std::max(widest, r * theta * projector.pixelsPerUnit / (projector.perspective ? d : 1.0));
    }
    return widest;
  }

  void addLonePatches();
  // Adds `group` of row r to `out`, split while wider than groupPixels (`split`: split it once
  // anyway), dropping what is outside the view.
  void addGroup(int r, Group group, std::vector<Group>& out, bool split);
  std::vector<OnCircle> onCircle(const Circle& c) const;
  void balanceCircles();
  void circleExponents();
  void addGroupItems();
};

void DrawSelection::Frame::addLonePatches() {
  for (size_t k = 0; k < selection.loneSlots_.size(); ++k) {
    const Box& b = selection.loneBoxes_[k];
    if (frustum.outside(b.lo, b.hi)) {
      ++counted.culled;
      continue;
    }
    // An edge's level comes from its Bezier polygon (3 legs, each within the box): 3x its diagonal.
    const int level = selection.loneHasJump_[k] ? kMaxSegments : segmentsFor(3.0 * across(b), settings);
    DrawItem item;
    item.slot = selection.loneSlots_[k];
    item.vertexBound = vertexBound(level, level);
    items.push_back(item);
    ++counted.patches;
  }
}

void DrawSelection::Frame::addGroup(int r, Group group, std::vector<Group>& out, bool split) {
  std::vector<Group> pending{group};
  while (!pending.empty()) {
    const Group g = pending.back();
    pending.pop_back();
    const Box& b = boxOf(r, g);
    if (frustum.outside(b.lo, b.hi)) {
      counted.culled += size_t(1) << g.log2;
      continue;
    }
    // A cap's group is a wedge cut by its rim's segments (up to 64) all the way to the pole: it may
    // be as wide as 64 segments (its rim gets as many as its width asks, circleExponents).
    const double widest = row(r).isCap ? kMaxSegments * groupPixels : groupPixels;
    if (g.log2 > 0 && (split || width(row(r), b) > widest)) {
      pending.push_back({g.log2 - 1, 2 * g.index + 1});
      pending.push_back({g.log2 - 1, 2 * g.index});
      split = false;  // only the group asked for is split, its halves are judged
      continue;
    }
    out.push_back(g);
  }
}

// A circle's vertices are agreed per domain: the groups on it, of both sides, are intervals of its
// finer side's sectors that nest or are apart (sizes are powers of two), and a domain is one that no
// other holds with those it holds. Within a domain one density (segments per sector, a power of two)
// cuts every group's edge; domains meet at a vertex of both sides. [O(groups log groups)]
std::vector<DrawSelection::Frame::OnCircle> DrawSelection::Frame::onCircle(const Circle& c) const {
  std::vector<OnCircle> found;
  const int64_t finer = std::max(row(c.inside).size, row(c.outside).size);
  for (int side = 0; side < 2; ++side) {
    const int r = side == 0 ? c.inside : c.outside;
    const int64_t scale = finer / row(r).size;
    for (size_t k = 0; k < groups[size_t(r)].size(); ++k) {
      const Group& g = groups[size_t(r)][k];
      found.push_back({(int64_t(g.index) << g.log2) * scale, (int64_t(1) << g.log2) * scale, side, k, 0});
    }
  }
  std::sort(found.begin(), found.end(), [](const OnCircle& a, const OnCircle& b) {
    return a.start != b.start ? a.start < b.start : a.size > b.size;
  });
  int64_t domainEnd = -1;
  int domain = -1;
  for (OnCircle& g : found) {
    if (g.start >= domainEnd) domainEnd = g.start + g.size, ++domain;
    g.domain = domain;
  }
  return found;
}

// Within a domain the groups stay within 2^kMaxGroupRatioLog2 of its smallest, so that one density
// gives each at least one segment and at most 64: larger ones split (until nothing changes).
void DrawSelection::Frame::balanceCircles() {
  for (bool changed = true; changed;) {
    changed = false;
    for (const Circle& c : selection.circles_) {
      const std::vector<OnCircle> found = onCircle(c);
      std::vector<int64_t> smallest(found.empty() ? 0 : size_t(found.back().domain) + 1, INT64_MAX);
      for (const OnCircle& g : found) smallest[size_t(g.domain)] = std::min(smallest[size_t(g.domain)], g.size);
      std::vector<uint8_t> split[2] = {std::vector<uint8_t>(groups[size_t(c.inside)].size(), 0),
                                       std::vector<uint8_t>(groups[size_t(c.outside)].size(), 0)};
      bool any = false;
      for (const OnCircle& g : found)
        if (g.size > (smallest[size_t(g.domain)] << kMaxGroupRatioLog2)) split[g.side][g.group] = 1, any = true;
      if (!any) continue;
      for (int side = 0; side < 2; ++side) {
        const int r = side == 0 ? c.inside : c.outside;
        std::vector<Group> kept;
        for (size_t k = 0; k < groups[size_t(r)].size(); ++k) {
          const Group& g = groups[size_t(r)][k];
          if (split[side][k] && g.log2 > 0) addGroup(r, g, kept, true), changed = true;
          else kept.push_back(g);
        }
        groups[size_t(r)] = std::move(kept);
      }
    }
  }
}

// Per domain its density: from the groups' lengths on the circle, at least one segment on its
// smallest group and at most 64 on its largest. Each group's edge on the circle gets 2^exponent
// segments (-1: the patches' own rule, where every group of the domain is a sector alone: the full
// draw's tessellation there).
void DrawSelection::Frame::circleExponents() {
  exponents.assign(groups.size(), {});
  for (size_t r = 0; r < groups.size(); ++r)
    for (auto& side : exponents[r]) side.assign(groups[r].size(), -1);
  const double mostSegments = double(std::clamp(settings.maxTessLevel, 1, kMaxSegments));
  for (const Circle& c : selection.circles_) {
    const std::vector<OnCircle> found = onCircle(c);
    const size_t domains = found.empty() ? 0 : size_t(found.back().domain) + 1;
    std::vector<int64_t> smallest(domains, INT64_MAX), largest(domains, 0);
    std::vector<double> wanted(domains, 0.0);  // segments per finer sector
    std::vector<uint8_t> grouped(domains, 0);
    for (const OnCircle& g : found) {
      const int r = g.side == 0 ? c.inside : c.outside;
      const Group& group = groups[size_t(r)][g.group];
      const Box& b = boxOf(r, group);
      // Its length on this circle: the outer arc of the row inside, the inner arc of the row
      // outside (at the same distance as the outer: rows are thin); a cap's widest.
      double pixels = g.side == 0 ? arc(b) : projector.pixels(b.innerArc, b.rimLo, b.rimHi);
      if (row(r).isCap) pixels = std::max(pixels, width(row(r), b));
      const size_t d = size_t(g.domain);
      smallest[d] = std::min(smallest[d], g.size);
      largest[d] = std::max(largest[d], g.size);
      // Segments per sector at tessPixels apiece (not rounded per group: a domain of many small
      // groups would ask a segment for each part of one).
      wanted[d] = std::max(wanted[d], std::min(pixels / std::max(settings.tessPixels, 0.5), mostSegments) / double(g.size));
      grouped[d] = grouped[d] || group.log2 > 0;
    }
    for (const OnCircle& g : found) {
      const size_t d = size_t(g.domain);
      if (!grouped[d]) continue;
      // Segments per finer sector 2^e: from one on the smallest up to what the lengths ask, while
      // the largest gets at most 64.
      int e = -log2Exact(smallest[d]);
      while (std::ldexp(1.0, e) < wanted[d] && std::ldexp(double(largest[d]), e + 1) <= kMaxSegments) ++e;
      const int r = g.side == 0 ? c.inside : c.outside;
      exponents[size_t(r)][g.side == 0 ? 1 : 0][g.group] = e + log2Exact(g.size);
    }
  }
}

void DrawSelection::Frame::addGroupItems() {
  for (size_t r = 0; r < groups.size(); ++r) {
    const Row& rw = row(int(r));
    if (!groups[r].empty()) ++counted.rows;
    for (size_t k = 0; k < groups[r].size(); ++k) {
      const Group& g = groups[r][k];
      DrawItem item;
      item.sector = g.index << g.log2;
      item.slot = uint32_t(selection.rowSlots_[size_t(rw.start + item.sector)]);
      item.rowStart = rw.start;
      item.rowSize = rw.size;
      item.groupLog2 = int8_t(g.log2);
      item.innerExponent = int8_t(exponents[r][0][k]);
      item.outerExponent = int8_t(exponents[r][1][k]);
      // Along v the circles' segments (or the T-junction rule's 64 where an edge keeps its own
      // rule); along u the radial edges' adaptive levels, within 3x the group's box.
      const int alongV = std::max(item.innerExponent < 0 && !rw.isCap ? kMaxSegments : 1 << std::max<int>(item.innerExponent, 0),
                                  item.outerExponent < 0 ? kMaxSegments : 1 << item.outerExponent);
      item.vertexBound = vertexBound(segmentsFor(3.0 * across(boxOf(int(r), g)), settings), alongV);
      items.push_back(item);
      counted.patches += size_t(1) << g.log2;
    }
  }
}

std::vector<DrawItem> DrawSelection::select(const ViewParams& view, const DrawSelectionSettings& settings,
                                            DrawSelectionStats* stats) const {
  Frame frame(*this, view, settings);
  frame.addLonePatches();
  // Per row its groups: from quarter turns down, split while wider than groupPixels.
  for (size_t r = 0; r < rows_.size(); ++r)
    for (int32_t k = 0; k < int32_t(rows_[r].pyramid[size_t(rows_[r].maxGroupLog2)].size()); ++k)
      frame.addGroup(int(r), {rows_[r].maxGroupLog2, k}, frame.groups[r], false);
  frame.balanceCircles();
  frame.circleExponents();
  frame.addGroupItems();
  // In slot order: a renderer's draws then take neighbouring slots together (patch_renderer.cpp).
  std::vector<DrawItem>& items = frame.items;
  std::sort(items.begin(), items.end(), [](const DrawItem& a, const DrawItem& b) { return a.slot < b.slot; });
  frame.counted.items = items.size();
  if (stats) *stats = frame.counted;
  return std::move(items);
}

}  // namespace polarview
