// Render tests of PatchRenderer: curvature colours, highlight lines, viewports (run under xvfb-run).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>

#include "render_test_support.h"

#include "core/mesh/obj_io.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"

namespace polarview {
namespace {

using test::colorDistance;

constexpr ShadingParams::ColorMap kAllMaps[] = {ShadingParams::ColorMap::Paper,
                                                ShadingParams::ColorMap::CoolWarm,
                                                ShadingParams::ColorMap::Viridis};

// Renders one renderer into a fresh offscreen target of w x h with a transparent background.
RgbaImage renderOffscreen(PatchRenderer& renderer, const ViewParams& view,
                          const ShadingParams& shading, const DisplayFlags& flags, int w, int h) {
  OffscreenTarget target;
  std::string error;
  REQUIRE_MESSAGE(target.create(w, h, 1, &error), error);
  target.bindAndClear(0, 0, 0, 0);
  renderer.draw(view, shading, flags);
  RgbaImage image = target.read();
  OffscreenTarget::bindDefault();
  return image;
}

bool covered(const uint8_t* pixel) { return pixel[3] == 255; }

TEST_CASE("renderer: a planar grid shows exactly the colour map's zero colour in K and H modes") {
  test::glContext();
  auto renderer = test::makeRenderer();
  // A tilted plane z = 0.3 x - 0.2 y: K = H = 0 everywhere, normal not along the view axis.
  renderer->setPatches(test::graphPatches([](double x, double y) { return 0.3 * x - 0.2 * y; },
                                          4, 4, -2.0, -2.0, 1.0));
  const ViewParams view = test::topView(renderer->center(), 2.5, {0, 0, 96, 96});
  for (ShadingParams::ColorMap map : kAllMaps)
    for (ShadingParams::Mode mode : {ShadingParams::Mode::Gaussian, ShadingParams::Mode::Mean}) {
      CAPTURE(int(map));
      CAPTURE(int(mode));
      const RgbaImage image = renderOffscreen(*renderer, view, test::flatCurvature(mode, map, 0.5f),
                                              test::surfaceOnly(), 96, 96);
      const glm::vec3 zero = colorMapCpu(map, 0.0f, 0.5f);
      int coveredCount = 0, worst = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
          if (covered(image.at(x, y))) {
            ++coveredCount;
            worst = std::max(worst, colorDistance(image.at(x, y), zero));
          }
      CHECK(coveredCount > image.width * image.height / 2);  // the plane fills the middle
      CHECK(worst <= 1);
    }
}

TEST_CASE("renderer: the pole of a paraboloid cap shows the colour of K = 4 and H = 2") {
  test::glContext();
  auto renderer = test::makeRenderer();
  for (int n : {5, 8, 12}) {
    renderer->setPatches(test::paraboloidCap(n, 1.0, 1.1));
    // An odd viewport puts the centre pixel's centre exactly on the pole.
    const int size = 65;
    const glm::dvec3 pole(0.0);
    const ViewParams view = test::topView(pole, 1.2, {0, 0, size, size});
    for (float range : {5.0f, 8.0f, 16.0f})
      for (ShadingParams::ColorMap map : kAllMaps) {
        CAPTURE(n);
        CAPTURE(range);
        CAPTURE(int(map));
        auto shading = test::flatCurvature(ShadingParams::Mode::Gaussian, map, range);
        shading.fixedTessLevel = 16;
        RgbaImage image = renderOffscreen(*renderer, view, shading, test::surfaceOnly(), size, size);
        CHECK(colorDistance(image.at(size / 2, size / 2), colorMapCpu(map, 4.0f, range)) <= 2);
        shading.mode = ShadingParams::Mode::Mean;
        image = renderOffscreen(*renderer, view, shading, test::surfaceOnly(), size, size);
        CHECK(colorDistance(image.at(size / 2, size / 2), colorMapCpu(map, 2.0f, range)) <= 2);
      }
  }
}

TEST_CASE("renderer: one-sided ranges (all K of one sign) colour as the CPU mirror, over the half of the map of their sign") {
  test::glContext();
  auto renderer = test::makeRenderer();
  renderer->setPatches(test::paraboloidCap(8, 1.0, 1.1));
  const int size = 65;
  const ViewParams view = test::topView(glm::dvec3(0.0), 1.2, {0, 0, size, size});
  // K = 4 at the pole: inside, below and above one-sided ranges; and a negative range it is above.
  for (const ColourInterval range : {ColourInterval{3.0, 5.0}, ColourInterval{3.9, 4.3}, ColourInterval{4.5, 6.0},
                                     ColourInterval{1.0, 3.0}, ColourInterval{-2.0, -1.0}})
    for (ShadingParams::ColorMap map : kAllMaps) {
      CAPTURE(range.low);
      CAPTURE(range.high);
      CAPTURE(int(map));
      auto shading = test::flatCurvature(ShadingParams::Mode::Gaussian, map, 1.0f);
      shading.range = range;
      shading.fixedTessLevel = 16;
      const RgbaImage image = renderOffscreen(*renderer, view, shading, test::surfaceOnly(), size, size);
      CHECK(colorDistance(image.at(size / 2, size / 2), colorMapCpu(map, 4.0, range)) <= 2);
    }
  // K = 4 in [3, 5] is the middle of the positive half: the paper map's yellow-green, not blue.
  const glm::vec3 middle = colorMapCpu(ShadingParams::ColorMap::Paper, 4.0, ColourInterval{3.0, 5.0});
  CHECK(middle.z == 0.0f);
  CHECK(middle.y > 0.5f);
}

TEST_CASE("renderer: the same K renders to the same colour in two side-by-side viewports") {
  test::glContext();
  // Two renderers (as for two schemes) sharing one shader library, zoomed differently.
  auto left = test::makeRenderer();
  auto right = test::makeRenderer();
  left->setPatches(test::paraboloidCap(6, 1.0, 1.05));
  right->setPatches(test::paraboloidCap(10, 1.0, 0.95, Point(5.0, -3.0, 2.0)));
  const int w = 65, h = 65;
  OffscreenTarget target;
  std::string error;
  REQUIRE(target.create(2 * w, h, 1, &error));
  for (float range : {4.5f, 10.0f}) {
    CAPTURE(range);
    target.bindAndClear(0, 0, 0, 0);
    auto shading = test::flatCurvature(ShadingParams::Mode::Gaussian, ShadingParams::ColorMap::Paper, range);
    shading.fixedTessLevel = 12;
    left->draw(test::topView(Point(0.0), 1.2, {0, 0, w, h}), shading, test::surfaceOnly());
    right->draw(test::topView(Point(5.0, -3.0, 2.0), 0.6, {w, 0, w, h}), shading,
                test::surfaceOnly());
    const RgbaImage image = target.read();
    const uint8_t* a = image.at(w / 2, h / 2);
    const uint8_t* b = image.at(w + w / 2, h / 2);
    for (int c = 0; c < 4; ++c) CHECK(std::abs(int(a[c]) - int(b[c])) <= 1);
    CHECK(colorDistance(a, colorMapCpu(ShadingParams::ColorMap::Paper, 4.0f, range)) <= 2);
  }
  OffscreenTarget::bindDefault();
}

TEST_CASE("renderer: highlight lines on a cylinder are stripes parallel to its rulings") {
  test::glContext();
  auto renderer = test::makeRenderer();
  // Parabolic cylinder z = -0.4 y^2: rulings along x; light lines along x as well.
  renderer->setPatches(test::graphPatches([](double, double y) { return -0.4 * y * y; }, 4, 4,
                                          -2.0, -2.0, 1.0));
  // Big enough that the stripes are wider than the anti-moire fade-out (~3 px per period).
  const int size = 256;
  const ViewParams view = test::topView(Point(0.0, 0.0, -1.0), 2.0, {0, 0, size, size});
  for (float spacing : {0.2f, 0.3f}) {
    CAPTURE(spacing);
    ShadingParams shading;
    shading.mode = ShadingParams::Mode::Highlight;
    shading.highlightDir = {1, 0, 0};
    shading.highlightPlaneNormal = {0, 0, 1};
    shading.highlightSpacing = spacing;
    shading.highlightWidth = 0.35f;
    const RgbaImage image = renderOffscreen(*renderer, view, shading, test::surfaceOnly(), size, size);
    // Dark = inside a light line. Image rows are lines of constant y (rulings).
    auto dark = [&](int x, int y) { return image.at(x, y)[0] < 60; };
    int transitionsAcross = 0, mismatches = 0, checked = 0;
    const int x0 = size / 8, x1 = size - size / 8;  // stay inside the surface
    for (int y = size / 8; y < size - size / 8; ++y) {
      // Along a row the classification is that of the row's middle pixel, except anti-aliased
      // pixels right at a stripe boundary, which are equally grey along the whole row.
      const bool reference = dark(size / 2, y);
      for (int x = x0; x < x1; ++x, ++checked) mismatches += dark(x, y) != reference;
      if (y > size / 8 && dark(size / 2, y) != dark(size / 2, y - 1)) ++transitionsAcross;
    }
    CHECK(mismatches <= checked / 200);
    CHECK(transitionsAcross >= 6);  // several stripes across the rulings
  }
}

TEST_CASE("renderer: overlays draw boundary curves in kind colours and pole markers") {
  test::glContext();
  auto renderer = test::makeRenderer();
  renderer->setPatches(test::paraboloidCap(6, 1.0, 1.0));
  renderer->setPoleMarkers({Point(0.0)});
  const int size = 97;
  const ViewParams view = test::topView(Point(0.0), 1.3, {0, 0, size, size});
  ShadingParams shading;
  DisplayFlags flags;
  flags.surface = false;
  flags.patchBoundaries = true;
  flags.poleMarkers = true;
  const RgbaImage image = renderOffscreen(*renderer, view, shading, flags, size, size);
  // The pole marker covers the centre; boundary pixels carry the PoleCap colour.
  CHECK(covered(image.at(size / 2, size / 2)));
  int capColored = 0, others = 0;
  const glm::vec3 capColor = patchKindColor(PatchKind::PoleCap);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!covered(image.at(x, y)) || std::abs(x - size / 2) + std::abs(y - size / 2) < 10) continue;
      (colorDistance(image.at(x, y), capColor) <= 2 ? capColored : others)++;
    }
  CHECK(capColored > 100);
  CHECK(others == 0);
}

TEST_CASE("renderer: highlight lines on a plane parallel to the light plane have the set spacing") {
  test::glContext();
  auto renderer = test::makeRenderer();
  // z = 0 under light lines along x in a plane z = const: the normal lines hit the light plane
  // right above P, so s = (P . E) / spacing with E = W x B = e_y: straight stripes, one per
  // spacing * boundingRadius in y.
  renderer->setPatches(test::graphPatches([](double, double) { return 0.0; }, 3, 3, -1.5, -1.5, 1.0));
  const int size = 160;
  const double half = 1.2;
  const ViewParams view = test::topView(Point(0.0), half, {0, 0, size, size});
  for (float spacing : {0.04f, 0.07f}) {
    CAPTURE(spacing);
    ShadingParams shading;
    shading.mode = ShadingParams::Mode::Highlight;
    shading.highlightDir = {1, 0, 0};
    shading.highlightPlaneNormal = {0, 0, 1};
    shading.highlightSpacing = spacing;
    shading.highlightWidth = 0.3f;
    const RgbaImage image = renderOffscreen(*renderer, view, shading, test::surfaceOnly(), size, size);
    auto dark = [&](int x, int y) { return image.at(x, y)[0] < 100; };
    // Centres of the dark runs down the middle column; rows must agree with the middle pixel.
    std::vector<double> centres;
    int runStart = -1, mismatches = 0;
    for (int y = 0; y < size; ++y) {
      for (int x = 8; x < size - 8; ++x) mismatches += dark(x, y) != dark(size / 2, y);
      const bool d = dark(size / 2, y);
      if (d && runStart < 0) runStart = y;
      if (!d && runStart >= 0) {
        if (runStart > 0) centres.push_back(0.5 * (runStart + y - 1));  // skip a cut-off first run
        runStart = -1;
      }
    }
    REQUIRE(centres.size() >= 4);
    const double measured = (centres.back() - centres.front()) / double(centres.size() - 1);
    const double expected = spacing * renderer->boundingRadius() / (2.0 * half) * size;  // pixels
    CHECK(measured == doctest::Approx(expected).epsilon(0.02));
    // Rows agree except for a few anti-aliased pixels sitting right at the dark/light threshold.
    CHECK(mismatches <= size * (size - 16) / 200);
  }
}

TEST_CASE("renderer: wireframe-only draws more edge pixels as the tessellation gets finer") {
  test::glContext();
  auto renderer = test::makeRenderer();
  renderer->setPatches(test::graphPatches([](double, double) { return 0.0; }, 2, 2, -1.0, -1.0, 1.0));
  const int size = 200;
  const ViewParams view = test::topView(Point(0.0), 1.1, {0, 0, size, size});
  DisplayFlags flags = test::surfaceOnly();
  flags.surface = false;
  flags.wireframe = true;
  int previous = 0;
  for (int level : {1, 2, 4}) {
    CAPTURE(level);
    ShadingParams shading;
    shading.fixedTessLevel = level;
    const RgbaImage image = renderOffscreen(*renderer, view, shading, flags, size, size);
    int wirePixels = 0, holes = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) (covered(image.at(x, y)) ? wirePixels : holes)++;
    CHECK(wirePixels > previous * 3 / 2);
    CHECK(holes > size * size / 3);  // the inside of the triangles stays empty
    previous = wirePixels;
  }
}

TEST_CASE("renderer: the control net is drawn along the mesh edges") {
  test::glContext();
  auto renderer = test::makeRenderer();
  renderer->setPatches(test::graphPatches([](double, double) { return 0.0; }, 2, 2, -1.0, -1.0, 1.0));
  // A 2 x 2 quad grid over [-1, 1]^2: its edges are the lines x, y in {-1, 0, 1}.
  PolyMesh net;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) net.points.push_back(Point(i - 1.0, j - 1.0, 0.0));
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      net.addFace({3 * j + i, 3 * j + i + 1, 3 * (j + 1) + i + 1, 3 * (j + 1) + i});
  renderer->setControlMesh(net);
  const int size = 101;  // pixel 50 is the centre, the lines x = +-1 fall on pixels 10 and 90
  const ViewParams view = test::topView(Point(0.0), 1.25, {0, 0, size, size});
  DisplayFlags flags = test::surfaceOnly();
  flags.surface = false;
  flags.controlNet = true;
  const RgbaImage image = renderOffscreen(*renderer, view, ShadingParams{}, flags, size, size);
  int onLines = 0, offLines = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!covered(image.at(x, y))) continue;
      const bool nearLine = std::min({std::abs(x - 10), std::abs(x - 50), std::abs(x - 90)}) <= 1 ||
                            std::min({std::abs(y - 10), std::abs(y - 50), std::abs(y - 90)}) <= 1;
      (nearLine ? onLines : offLines)++;
    }
  CHECK(onLines >= 6 * 75);  // six lines of ~80 pixels each
  CHECK(offLines == 0);
}

TEST_CASE("control net: light lines where the surface is hidden, dark lines over it, faint where it runs behind") {
  test::glContext();
  auto renderer = test::makeRenderer();
  // A flat 3x3 grid of patches and, 0.3 below it, a 4x4 control net: every net line runs behind
  // the surface (seen from above) except where it leaves the surface's footprint.
  renderer->setPatches(test::graphPatches([](double, double) { return 0.0; }, 3, 3, -1.5, -1.5, 1.0));
  PolyMesh net;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) net.points.push_back({-2.0 + i, -2.0 + j, -0.3});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) net.addFace({Index(5 * j + i), Index(5 * j + i + 1), Index(5 * j + i + 6), Index(5 * j + i + 5)});
  renderer->setControlMesh(net);
  const int size = 200;
  const ViewParams view = test::topView(Point(0.0), 2.4, {0, 0, size, size});
  ShadingParams shading;
  DisplayFlags netOnly;
  netOnly.surface = false;
  netOnly.controlNet = true;
  netOnly.poleMarkers = false;
  auto count = [&](const RgbaImage& image, auto predicate) {
    int n = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) n += predicate(image.at(x, y));
    return n;
  };
  // Net only: light lines (visible on the dark viewer background).
  const RgbaImage alone = renderOffscreen(*renderer, view, shading, netOnly, size, size);
  const int light = count(alone, [](const uint8_t* p) { return p[3] == 255 && p[0] > 180; });
  CHECK(light > 5 * size);
  // With the surface: the lines behind it show as a blend of net and surface colour (darker than
  // the surface, lighter than the net), not as gaps.
  DisplayFlags both = netOnly;
  both.surface = true;
  const RgbaImage drawn = renderOffscreen(*renderer, view, shading, both, size, size);
  const RgbaImage plain = renderOffscreen(*renderer, view, shading, test::surfaceOnly(), size, size);
  int faint = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const int with = drawn.at(x, y)[1], without = plain.at(x, y)[1];
      faint += drawn.at(x, y)[3] == 255 && with < without - 20 && with > 40;
    }
  CHECK(faint > 3 * size);
  CHECK(count(drawn, [](const uint8_t* p) { return p[3] != 0 && p[3] != 255; }) == 0);  // alpha kept
}

}  // namespace
}  // namespace polarview

namespace polarview {

// A level step on one hierarchy uploads only the regular patches not yet on the GPU (setPatches'
// stable sequence) and the new level's caps: what the GPU then evaluates must be what a fresh
// upload of the new level evaluates, up and down, after the buffers grew, and after a deeper level
// was shown (its regular patches stay on the GPU, beyond the shallower set's).
TEST_CASE("renderer: level steps keeping the regular patches on the GPU evaluate as fresh uploads") {
  const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  AdaptiveRefinement refinement(mesh, RefineOptions{Scheme::C2PS, 4, false});
  LevelPatchCache cache;
  auto stepped = test::makeRenderer();
  constexpr uint64_t kStamp = 7;
  int deepestShown = -1;
  for (int level : {1, 3, 2, 4, 0, 4, 3}) {
    CAPTURE(level);
    const PatchSet set = cache.patchSet(refinement, level);
    const size_t regular = cache.sharedPrefix(level, level);
    stepped->setPatches(set.patches, kStamp, regular);
    // Every regular patch of a level shown before is reused.
    CHECK(stepped->lastReusedPatches() == (deepestShown < 0 ? 0 : cache.sharedPrefix(deepestShown, level)));
    CHECK(stepped->slotsInUse() >= set.patches.size());
    deepestShown = std::max(deepestShown, level);
    auto fresh = test::makeRenderer();
    fresh->setPatches(set.patches);
    const std::vector<SurfaceProbe> a = stepped->probeSurface(3), b = fresh->probeSurface(3);
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() >= set.patches.size());
    double worstPosition = 0.0, worstK = 0.0;
    size_t indexMismatch = 0;
    for (size_t k = 0; k < a.size(); ++k) {
      indexMismatch += a[k].patch != b[k].patch;
      worstPosition = std::max(worstPosition, glm::length(a[k].position - b[k].position));
      worstK = std::max(worstK, double(std::abs(a[k].gaussian - b[k].gaussian)) / (1.0 + std::abs(b[k].gaussian)));
    }
    CHECK(indexMismatch == 0);  // probes name the patch of the set, whatever slot it lies in
    // Both are float evaluations of the same patches in their own frames; the centre differs.
    CHECK(worstPosition < 1e-5);
    CHECK(worstK < 1e-3);
  }
}

}  // namespace polarview
