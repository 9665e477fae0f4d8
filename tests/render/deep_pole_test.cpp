// Deep levels: RTS and BPS refine a pole radially, so at level L the innermost ring and the cap are
// ~2^-L of the model (1e-6 at level 20), and C2PS's ring patches at level L are ~2^-L long and
// 12 * 2^L / pi times thinner. Float world coordinates resolve ~6e-8 near 1: the renderer draws
// each patch in its own frame, as forward differences, relative to the eye (patch_renderer.cpp,
// "Precision"). These tests check the GPU against the CPU on such patches and look at a level-20
// pole from as close as its innermost ring.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/mesh/shapes.h"
#include "core/spline/patch.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "render_test_support.h"
#include "pipeline/orbit_camera.h"

namespace polarview {
namespace {

// A unit globe with two valence-12 poles, refined feature-adaptively as view and render do. Its
// poles are ~1 from the model's centre, where float steps are 6e-8.
std::vector<Patch> deepGlobe(Scheme scheme, int levels) {
  RefineOptions options;
  options.scheme = scheme;
  options.levels = levels;
  return extractPatches(AdaptiveRefinement(shapes::globe(12, 6, 1.0), options)).patches;
}

// The cap of pole 0 that starts at angle 0.
const Patch& firstCap(const std::vector<Patch>& patches) {
  for (const Patch& patch : patches)
    if (patch.kind == PatchKind::PoleCap && patch.pole == 0 && patch.sector == 0) return patch;
  FAIL("no pole cap");
  return patches.front();
}

// A point of the patch (relative to Patch::origin) and its size: the cap's pole and boundary, or
// the face's corners.
glm::dvec3 patchPoint(const Patch& patch) { return patch.kind == PatchKind::PoleCap ? patch.cp[0] : patch.cp[5]; }
double patchSize(const Patch& patch) {
  if (patch.kind == PatchKind::PoleCap) return glm::length(patch.cp[7] - patch.cp[0]);
  return std::max(glm::length(patch.cp[10] - patch.cp[5]), glm::length(patch.cp[9] - patch.cp[6]));
}

// evaluatePatch with the patch moved to one of its own points first (in double), so the reference
// does not lose the digits of a small patch far from the origin. K and H do not change.
SurfacePoint evaluateNearby(const Patch& patch, double u, double v) {
  Patch moved = patch;
  const glm::dvec3 near = patchPoint(patch);
  for (int k = 0; k < 16; ++k)
    if (isPositionPoint(patch.kind, k)) moved.cp[k] -= near;
  moved.origin = glm::dvec3(0.0);
  SurfacePoint point = evaluatePatch(moved, u, v);
  point.position += patch.origin + near;
  return point;
}

// Perspective eye `distance` from `target`, raised 50 degrees, with the viewer's planes
// (orbit_camera.cpp: near no further than distance / 100; far past the model's sphere).
ViewParams lookAtPole(const glm::dvec3& target, double distance, int width, int height) {
  ViewParams view;
  const double pitch = glm::radians(50.0), yaw = glm::radians(-60.0);
  const glm::dvec3 back(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
  const glm::dvec3 eye = target + distance * back;
  view.eye = eye;
  view.view = glm::mat4(glm::lookAt(eye, target, glm::dvec3(0, 0, 1)));
  const double farPlane = distance + 4.0;
  view.proj = glm::mat4(glm::perspective(glm::radians(35.0), double(width) / height,
                                         std::min(farPlane * 1e-4, distance * 1e-2), farPlane));
  view.viewport = {0, 0, width, height};
  return view;
}

struct DeepAgreement {
  double position = 0.0;  // worst |GPU - CPU| / patch size, the GPU's as drawn (relative to the eye)
  double curvature = 0.0;  // worst |K_GPU - K_CPU| / max(|K_CPU|, 0.1 |K|max), same for H
  size_t samples = 0;
};

// GPU against CPU on the patches of pole 0 of at least level `from`, all patches uploaded (the
// model's centre is where it would be in the viewer), the vertices where draw() puts them for an
// eye 1e-6 above the pole.
DeepAgreement compareDeepPatches(PatchRenderer& renderer, const std::vector<Patch>& patches, int from) {
  renderer.setPatches(patches);
  glm::dvec3 pole(0.0);
  for (const Patch& patch : patches)
    if (patch.kind == PatchKind::PoleCap && patch.pole == 0) pole = patch.origin + patch.cp[0];
  ShadingParams fixed;
  fixed.fixedTessLevel = 6;
  std::vector<SurfaceProbe> probes = renderer.probeSurface(lookAtPole(pole, 1e-6, 320, 240), fixed);
  probes.erase(std::remove_if(probes.begin(), probes.end(),
                              [&](const SurfaceProbe& probe) {
                                const Patch& patch = patches.at(size_t(probe.patch));
                                return patch.level < from || patch.pole != 0;
                              }),
               probes.end());
  std::vector<SurfacePoint> cpu;
  double largestK = 0.0, largestH = 0.0;
  for (const SurfaceProbe& probe : probes) {
    cpu.push_back(evaluateNearby(patches.at(size_t(probe.patch)), probe.u, probe.v));
    largestK = std::max(largestK, std::abs(cpu.back().gaussian));
    largestH = std::max(largestH, std::abs(cpu.back().mean));
  }
  DeepAgreement a;
  a.samples = probes.size();
  for (size_t k = 0; k < probes.size(); ++k) {
    const Patch& patch = patches[size_t(probes[k].patch)];
    const SurfacePoint& c = cpu[k];
    a.position = std::max(a.position, glm::length(probes[k].position - c.position) / patchSize(patch));
    a.curvature = std::max({a.curvature,
                            std::abs(probes[k].gaussian - c.gaussian) / std::max(std::abs(c.gaussian), 0.1 * largestK),
                            std::abs(probes[k].mean - c.mean) / std::max(std::abs(c.mean), 0.1 * largestH)});
  }
  return a;
}

TEST_CASE("deep pole: the GPU evaluates the deepest rings and caps as evaluatePatch does, relative to their size") {
  test::glContext();
  auto renderer = test::makeRenderer();
  struct Case {
    Scheme scheme;
    int level, from;  // refinement level; patches of levels >= from are compared
  };
  // RTS, BPS: rings of ~1e-6 at level 20. C2PS: at level 10 a ring patch is ~1e-3 long and 4000
  // times thinner, so its curvature across is a 1e-7 part of its control points' spread.
  for (const Case c : {Case{Scheme::RTS, 20, 17}, Case{Scheme::BPS, 20, 17}, Case{Scheme::C2PS, 10, 9}}) {
    const std::vector<Patch> patches = deepGlobe(c.scheme, c.level);
    const size_t deep = size_t(std::count_if(patches.begin(), patches.end(), [&](const Patch& patch) {
      return patch.level >= c.from && patch.pole == 0;
    }));
    const DeepAgreement a = compareDeepPatches(*renderer, patches, c.from);
    CAPTURE(int(c.scheme));
    MESSAGE("scheme " << int(c.scheme) << " level " << c.level << ": " << deep << " patches, " << a.samples
                      << " samples, worst position / patch size " << a.position << ", worst K, H " << a.curvature);
    CHECK(a.samples >= deep * 6 * 6);
    // Measured 3e-7..1.2e-6 and 1e-6..8e-6. Before (float world coordinates): position ~0.03 of a
    // level-20 patch, and K, H wrong by factors (they are 1e-7 parts of the coordinates). A lost lo
    // half of a double (GCC folding double(float(x)) to x) moved the caps by 0.015 of their size.
    CHECK(a.position < 1e-5);
    CHECK(a.curvature < 1e-4);
  }
}

struct ImageStats {
  int uncovered = 0;  // pixels no patch was drawn on (alpha 0)
  int speckles = 0;   // pixels differing from all 4 neighbours by more than 24 (of 255) in a channel
};

ImageStats imageStats(const RgbaImage& image) {
  ImageStats stats;
  auto differs = [&](const uint8_t* p, int x, int y) {
    const uint8_t* q = image.at(x, y);
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(p[c]) - int(q[c])) > 24) return true;
    return false;
  };
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = image.at(x, y);
      stats.uncovered += p[3] == 0;
      if (x > 0 && y > 0 && x + 1 < image.width && y + 1 < image.height)
        stats.speckles += differs(p, x - 1, y) && differs(p, x + 1, y) && differs(p, x, y - 1) && differs(p, x, y + 1);
    }
  return stats;
}

TEST_CASE("deep pole: a level-20 pole seen from 1e-3 down to 1e-7 of the model is covered, smooth and of its curvature") {
  test::glContext();
  auto renderer = test::makeRenderer();
  const int width = 320, height = 240;
  OffscreenTarget target;
  std::string error;
  REQUIRE_MESSAGE(target.create(width, height, 1, &error), error);
  for (const Scheme scheme : {Scheme::RTS, Scheme::BPS}) {
    const std::vector<Patch> patches = deepGlobe(scheme, 20);
    renderer->setPatches(patches);
    // The view's centre is the pole: its colour is that of the cap's K there (BPS: 0, the tangent
    // plane; RTS: the Taylor expansion's).
    const Patch& cap = firstCap(patches);
    const glm::dvec3 pole = cap.origin + cap.cp[0];
    const ShadingParams shading = test::flatCurvature(ShadingParams::Mode::Gaussian, ShadingParams::ColorMap::Paper, 2.0f);
    const glm::vec3 poleColour = colorMapCpu(shading.colormap, float(evaluatePatch(cap, 0.0, 0.0).gaussian), shading.range);
    // 1e-5: rings 14.. and the cap (radius ~2e-6); 1e-6: the cap fills the view; 1e-7: 6e-8 wide.
    for (const double distance : {1e-3, 1e-5, 1e-6, 1e-7}) {
      CAPTURE(int(scheme));
      CAPTURE(distance);
      target.bindAndClear(0, 0, 0, 0);
      renderer->draw(lookAtPole(pole, distance, width, height), shading, test::surfaceOnly());
      const RgbaImage image = target.read();
      const ImageStats stats = imageStats(image);
      const int poleError = test::colorDistance(image.at(width / 2, height / 2), poleColour);
      MESSAGE("scheme " << int(scheme) << " from " << distance << ": " << stats.uncovered << " uncovered, "
                        << stats.speckles << " speckles, pole colour off by " << poleError);
      CHECK(stats.uncovered == 0);
      // From 1e-5 the cap is ~80 pixels across and its rim, where its K meets the ring's with a
      // jump (it is C1 there, docs/rings-and-pole.md#closing-the-hole-the-pole-cap), is a band a
      // pixel or two wide: not speckle.
      if (distance != 1e-5) CHECK(stats.speckles == 0);
      // From 1e-6 the cap fills the view and the pixel at the pole is the pole's colour; further
      // out it is interpolated over the tessellation around the pole (or, from 1e-3, it is rings).
      if (distance <= 1e-6) CHECK(poleError <= 3);
    }
  }
  OffscreenTarget::bindDefault();
}

TEST_CASE("deep pole: the orbit camera zooms to 1e-12 of the target and keeps a surface 1e-6 away in its planes") {
  OrbitCamera camera;
  camera.target = glm::dvec3(0.0, 0.0, 0.97);
  camera.distance = 1.0;
  for (int notch = 0; notch < 400; ++notch) camera.zoom(1.0);
  CHECK(camera.distance == doctest::Approx(1e-12 * glm::length(camera.target)));
  // The eye 1e-6 above a pole of a unit model, looking at it: the pole lies between the planes.
  camera.distance = 1e-6;
  const glm::dmat4 clip = glm::dmat4(camera.projectionMatrix(1.0, glm::dvec3(0.0), 1.0)) * glm::dmat4(camera.viewMatrix());
  const glm::dvec4 pole = clip * glm::dvec4(camera.target, 1.0);
  CHECK(pole.w > 0.0);
  CHECK(std::abs(pole.z / pole.w) < 1.0);
  // So does a point half-way to the eye.
  const glm::dvec4 nearer = clip * glm::dvec4(0.5 * (camera.target + camera.eye()), 1.0);
  CHECK(std::abs(nearer.z / nearer.w) < 1.0);
}

}  // namespace
}  // namespace polarview
