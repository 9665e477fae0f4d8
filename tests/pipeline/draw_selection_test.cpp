// Draw selection (pipeline/draw_selection.h): every patch in view is drawn exactly once, alone or in
// a group of its row's sectors; the two sides of each link circle are cut into the same segments
// per turn; close to the pole the primitives are bounded by the pixels, not by the patches.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include <glm/geometric.hpp>

#include "core/mesh/shapes.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "pipeline/draw_selection.h"
#include "pipeline/orbit_camera.h"

using namespace polarview;

namespace {

struct Scene {
  std::vector<Patch> patches;
  DrawSelection selection;
  glm::dvec3 lo{1e300}, hi{-1e300};
  Point pole{0.0};
};

Scene capScene(int level) {
  Scene scene;
  const AdaptiveRefinement refinement(shapes::polarCap(12, 3), {Scheme::C2PS, level, false});
  scene.patches = extractPatches(refinement).patches;
  std::vector<uint32_t> slots(scene.patches.size());
  for (size_t p = 0; p < slots.size(); ++p) slots[p] = uint32_t(p);
  scene.selection.build(scene.patches, slots);
  for (const Patch& patch : scene.patches)
    for (int k = 0; k < 16; ++k)
      if (isPositionPoint(patch.kind, k)) {
        scene.lo = glm::min(scene.lo, patch.origin + patch.cp[size_t(k)]);
        scene.hi = glm::max(scene.hi, patch.origin + patch.cp[size_t(k)]);
      }
  for (const Patch& patch : scene.patches)
    if (patch.kind == PatchKind::PoleCap) scene.pole = patch.origin + patch.cp[0];
  return scene;
}

ViewParams viewOf(const OrbitCamera& camera, const Scene& scene, int width, int height) {
  ViewParams view;
  view.viewport = glm::ivec4(0, 0, width, height);
  view.view = camera.viewMatrix();
  view.proj = camera.projectionMatrix(double(width) / height, 0.5 * (scene.lo + scene.hi), 0.5 * glm::length(scene.hi - scene.lo));
  view.eye = camera.eye();
  return view;
}

// Each drawn slot once; returns how many were drawn.
size_t checkCoverage(const Scene& scene, const std::vector<DrawItem>& items) {
  std::vector<int> drawn(scene.patches.size(), 0);
  const std::vector<int32_t>& rowSlots = scene.selection.rowSlots();
  for (const DrawItem& item : items) {
    if (item.rowStart < 0) {
      CHECK(item.groupLog2 == 0);
      ++drawn[item.slot];
      continue;
    }
    CHECK(uint32_t(rowSlots[size_t(item.rowStart + item.sector)]) == item.slot);
    for (int k = 0; k < (1 << item.groupLog2); ++k) ++drawn[size_t(rowSlots[size_t(item.rowStart + (item.sector + k) % item.rowSize)])];
  }
  CHECK(std::all_of(drawn.begin(), drawn.end(), [](int n) { return n <= 1; }));
  return size_t(std::count(drawn.begin(), drawn.end(), 1));
}

// Per circle (the level and link of the row outside it): both sides cut it into the same vertices
// where both are drawn. Positions in 1/64 of the circle's finer sectors; each item's edge on it has
// 1..64 segments.
void checkCircles(const Scene& scene, const std::vector<DrawItem>& items) {
  struct Edge {
    int64_t start, size, segments;  // in units of the finer side's sectors; its row's size
    int rowSize;
  };
  std::map<std::tuple<int, int>, std::vector<Edge>> sides[2];  // [0]: the row inside the circle
  for (const DrawItem& item : items) {
    if (item.rowStart < 0) continue;
    const Patch& patch = scene.patches[item.slot];
    for (int edge = 0; edge < 2; ++edge) {
      const int exponent = edge == 0 ? item.innerExponent : item.outerExponent;
      if (exponent < 0) continue;
      CHECK(exponent <= 6);
      // The circle inside row (m, 3) is outside row (m, 2); inside (m, 2): outside (m + 1, 3) or
      // the caps (m, 0).
      std::tuple<int, int> circle;
      if (edge == 0) circle = {patch.level, patch.link};
      else if (patch.link == 2) circle = {patch.level, 3};
      else if (patch.link == 3) circle = {patch.level - 1, 2};
      else circle = {patch.level, 2};  // a cap's rim: inside ring (level, 2)
      sides[edge == 0 ? 1 : 0][circle].push_back({item.sector, int64_t(1) << item.groupLog2, int64_t(1) << exponent, item.rowSize});
    }
  }
  size_t circles = 0;
  for (const auto& [circle, inside] : sides[0]) {
    const auto found = sides[1].find(circle);
    if (found == sides[1].end()) continue;
    const std::vector<Edge>& outside = found->second;
    ++circles;
    CAPTURE(std::get<0>(circle));
    CAPTURE(std::get<1>(circle));
    int finer = 0;
    for (const std::vector<Edge>* edges : {&inside, &outside})
      for (const Edge& e : *edges) finer = std::max(finer, e.rowSize);
    // Per side its vertices and the stretches it covers, in 1/64 finer sector.
    std::set<int64_t> vertices[2];
    std::vector<std::pair<int64_t, int64_t>> covered[2];
    int side = 0;
    for (const std::vector<Edge>* edges : {&inside, &outside}) {
      for (const Edge& e : *edges) {
        const int64_t scale = 64 * (finer / e.rowSize), start = e.start * scale, length = e.size * scale;
        REQUIRE(length % e.segments == 0);
        for (int64_t k = 0; k <= e.segments; ++k) vertices[side].insert(start + k * (length / e.segments));
        covered[side].push_back({start, start + length});
      }
      ++side;
    }
    for (int a = 0; a < 2; ++a)
      for (int64_t v : vertices[a]) {
        const bool inOther = std::any_of(covered[1 - a].begin(), covered[1 - a].end(),
                                         [&](const auto& c) { return v > c.first && v < c.second; });
        if (inOther) CHECK(vertices[1 - a].count(v) == 1);
      }
  }
  CHECK(circles > 0);
}

}  // namespace

TEST_CASE("draw selection: a framed C2PS cap draws each patch once; every ring is a row") {
  const Scene scene = capScene(8);
  // Level 0's inner row (the cap's 3 links leave one), two rows a level 1..8, the caps.
  CHECK(scene.selection.groupedRows() == 1 + 2 * 8 + 1);
  OrbitCamera camera;
  camera.frame(scene.lo, scene.hi, 4.0 / 3.0);
  const ViewParams view = viewOf(camera, scene, 800, 600);
  DrawSelectionSettings settings;
  settings.viewportHeight = 600;
  DrawSelectionStats stats;
  const std::vector<DrawItem> items = scene.selection.select(view, settings, &stats);
  CHECK(checkCoverage(scene, items) == scene.patches.size());  // all in view
  CHECK(stats.culled == 0);
  CHECK(stats.patches == scene.patches.size());
  CHECK(stats.items == items.size());
  // The deep rings are below a pixel: far fewer primitives than patches.
  CHECK(items.size() * 10 < scene.patches.size());
  checkCircles(scene, items);
}

TEST_CASE("draw selection: close to the pole the primitives follow the pixels, and what is outside is culled") {
  const Scene scene = capScene(12);
  for (double distance : {1e-2, 1e-3})
    for (double pitch : {89.0, 35.0}) {
      CAPTURE(distance);
      CAPTURE(pitch);
      OrbitCamera camera;
      camera.target = scene.pole;
      camera.distance = distance;
      camera.pitchDeg = pitch;
      const ViewParams view = viewOf(camera, scene, 800, 600);
      DrawSelectionSettings settings;
      settings.viewportHeight = 600;
      DrawSelectionStats stats;
      const std::vector<DrawItem> items = scene.selection.select(view, settings, &stats);
      const size_t drawn = checkCoverage(scene, items);
      CHECK(drawn == stats.patches);
      CHECK(drawn + stats.culled == scene.patches.size());
      CHECK(stats.culled > 0);
      // 245,724 patches; a few thousand primitives (an 800x600 view holds 3,300 squares of 12 pixels).
      CHECK(scene.patches.size() > 240000);
      CHECK(items.size() < 5000);
      checkCircles(scene, items);
    }
}
