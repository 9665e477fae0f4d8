// The GPU evaluator (shaders/common/patch_eval.glsl, read back by transform feedback) against the
// CPU evaluatePatch (src/core/spline/bicubic_patch.cpp) and against closed-form curvature.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <map>
#include <set>

#include "core/mesh/obj_io.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "render_test_support.h"

namespace polarview {
namespace {

// Random but smooth B-spline patches: a jittered grid with random heights, of the given kind.
std::vector<Patch> randomBSplinePatches(std::mt19937& rng, PatchKind kind, int count) {
  std::uniform_real_distribution<double> jitter(-0.2, 0.2), height(-0.6, 0.6);
  std::vector<Patch> patches;
  for (int k = 0; k < count; ++k) {
    Patch patch;
    patch.kind = kind;
    patch.ring = kind == PatchKind::PolarRing ? k : -1;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        patch.cp[4 * j + i] = Point(i + jitter(rng) + 5.0 * k, j + jitter(rng), height(rng));
    patches.push_back(patch);
  }
  return patches;
}

// Random Taylor caps: random p0..p5 (p1, p2 roughly orthogonal so the tangent plane is regular;
// p3..p5 zeroed for Taylor order 1, as extraction stores BPS's) and ring data near the full
// expansion on the circle r = R = kPoleCapRadius: boundary points b, first and second radial
// derivatives e, f.
std::vector<Patch> randomPoleCaps(std::mt19937& rng, int n, int order) {
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  const double R = kPoleCapRadius;
  Point p[6] = {Point(noise(rng), noise(rng), 3.0),           Point(0.75, noise(rng), noise(rng)),
                Point(noise(rng), 0.75, noise(rng)),          Point(noise(rng), noise(rng), 0.4),
                Point(noise(rng), noise(rng), 0.15 + noise(rng)), Point(noise(rng), noise(rng), -0.1)};
  std::vector<Point> b(n), e(n), f(n);
  for (int j = 0; j < n; ++j) {
    const double t = 6.283185307179586 * j / n, c = std::cos(t), s = std::sin(t), x = R * c, y = R * s;
    const Point Q = p[3] + p[4] * (c * c - s * s) + p[5] * (2 * c * s);
    b[j] = p[0] + p[1] * x + p[2] * y + p[3] * (x * x + y * y) + p[4] * (x * x - y * y) +
           p[5] * (2 * x * y) + Point(noise(rng), noise(rng), noise(rng));
    e[j] = p[1] * c + p[2] * s + 2.0 * R * Q + Point(noise(rng), noise(rng), noise(rng));
    f[j] = 2.0 * Q + Point(noise(rng), noise(rng), noise(rng));
  }
  // The ring is curved either way; an order-1 cap keeps the tangent plane only (BPS).
  if (order < 2) p[3] = p[4] = p[5] = Point(0.0);
  std::vector<Patch> caps;
  for (int j = 0; j < n; ++j) {
    Patch patch;
    patch.kind = PatchKind::PoleCap;
    patch.sector = j;
    patch.sectorCount = n;
    for (int k = 0; k < 6; ++k) patch.cp[k] = p[k];
    for (int k = 0; k < 4; ++k) patch.cp[6 + k] = b[(j - 1 + k + n) % n];
    for (int k = 0; k < 4; ++k) patch.cp[12 + k] = e[(j - 1 + k + n) % n];
    for (int k = 0; k < 4; ++k) capSecondPoint(patch, k) = f[(j - 1 + k + n) % n];
    caps.push_back(patch);
  }
  return caps;
}

struct Agreement {
  double position = 0, gaussian = 0, mean = 0;  // worst errors relative to the scales below
  size_t samples = 0;
};

// Worst GPU-vs-CPU differences: positions relative to the bounding radius, K and H relative to
// max(|CPU value|, 1% of the largest |value| in the set), so zero crossings do not divide by 0.
Agreement compareWithCpu(PatchRenderer& renderer, const std::vector<Patch>& patches, int level) {
  const std::vector<SurfaceProbe> probes = renderer.probeSurface(level);
  std::vector<SurfacePoint> cpu;
  double maxK = 0, maxH = 0;
  for (const SurfaceProbe& probe : probes) {
    cpu.push_back(evaluatePatch(patches.at(probe.patch), probe.u, probe.v));
    maxK = std::max(maxK, std::abs(cpu.back().gaussian));
    maxH = std::max(maxH, std::abs(cpu.back().mean));
  }
  Agreement a;
  a.samples = probes.size();
  for (size_t k = 0; k < probes.size(); ++k) {
    const SurfacePoint& c = cpu[k];
    a.position = std::max(a.position, glm::length(probes[k].position - c.position) /
                                          renderer.boundingRadius());
    a.gaussian = std::max(a.gaussian, std::abs(probes[k].gaussian - c.gaussian) /
                                          std::max(std::abs(c.gaussian), 0.01 * maxK));
    a.mean = std::max(a.mean, std::abs(probes[k].mean - c.mean) /
                                  std::max(std::abs(c.mean), 0.01 * maxH));
  }
  return a;
}

TEST_CASE("gpu evaluator: K, H and positions equal evaluatePatch for every patch kind") {
  test::glContext();
  auto renderer = test::makeRenderer();
  std::mt19937 rng(20090801);
  struct Case {
    std::string name;
    std::vector<Patch> patches;
  };
  std::vector<Case> cases;
  for (PatchKind kind : {PatchKind::Regular, PatchKind::Boundary, PatchKind::PolarRing, PatchKind::EndCap})
    cases.push_back({patchKindName(kind), randomBSplinePatches(rng, kind, 12)});
  for (int n : {3, 6, 17}) {
    cases.push_back({"pole-cap order 2", randomPoleCaps(rng, n, 2)});
    cases.push_back({"pole-cap order 1", randomPoleCaps(rng, n, 1)});
  }
  for (const Case& c : cases) {
    CAPTURE(c.name);
    CAPTURE(c.patches.size());
    renderer->setPatches(c.patches);
    const int level = 8;
    const Agreement a = compareWithCpu(*renderer, c.patches, level);
    MESSAGE(c.name << ": " << a.samples << " samples, worst position " << a.position << ", K "
                   << a.gaussian << ", H " << a.mean);
    // Every patch's (level+1)^2 grid comes back (caps: the pole edge has 2 vertices).
    CHECK(a.samples >= c.patches.size() * (level + 1) * level);
    CHECK(a.position < 2e-6);
    CHECK(a.gaussian < 1e-4);
    CHECK(a.mean < 1e-4);
  }
}

TEST_CASE("gpu evaluator: a quadratic graph has its closed-form K and H at every probe") {
  test::glContext();
  auto renderer = test::makeRenderer();
  // z = a x^2 + b y^2 + c x y: B-splines reproduce it up to a constant (render_test_support.h).
  for (const auto& [a, b, c] : {std::tuple{0.5, 0.5, 0.0}, std::tuple{0.3, -0.7, 0.2},
                                std::tuple{0.0, 0.8, 0.0}, std::tuple{-0.4, -0.1, 0.6}}) {
    CAPTURE(a);
    CAPTURE(b);
    CAPTURE(c);
    const auto patches = test::graphPatches(
        [=](double x, double y) { return a * x * x + b * y * y + c * x * y; }, 3, 3, -1.5, -1.5, 1.0);
    renderer->setPatches(patches);
    double worstK = 0, worstH = 0;
    for (const SurfaceProbe& p : renderer->probeSurface(6)) {
      const double x = p.position.x, y = p.position.y;
      const auto exact = test::graphCurvature(2 * a * x + c * y, 2 * b * y + c * x, 2 * a, 2 * b, c);
      worstK = std::max(worstK, std::abs(p.gaussian - exact.gaussian));
      worstH = std::max(worstH, std::abs(p.mean - exact.mean));
    }
    // Curvatures here are O(1): absolute 1e-5 is float round-off, far below any colour step.
    CHECK(worstK < 1e-5);
    CHECK(worstH < 1e-5);
  }
}

TEST_CASE("gpu evaluator: the pole of a Taylor cap has exactly the expansion's K and H") {
  test::glContext();
  auto renderer = test::makeRenderer();
  for (int n : {4, 7, 24}) {
    for (double scale : {0.9, 1.3}) {
      renderer->setPatches(test::paraboloidCap(n, 0.8, scale));
      int poleSamples = 0;
      for (const SurfaceProbe& p : renderer->probeSurface(4)) {
        if (p.u != 0.0f) continue;
        ++poleSamples;
        CHECK(p.gaussian == doctest::Approx(4.0).epsilon(1e-6));
        CHECK(p.mean == doctest::Approx(2.0).epsilon(1e-6));
        CHECK(glm::length(p.position) < 1e-6);
      }
      CHECK(poleSamples >= 2 * n);  // both ends of the degenerate edge of every sector
    }
  }
}

}  // namespace
}  // namespace polarview

namespace polarview {
namespace {

// Parameters along the edge where patch `a`'s side meets its neighbour (sorted, rounded to 1e-4).
std::vector<long> edgeParameters(const std::vector<SurfaceProbe>& probes, int patch, bool uEdge,
                                 float edgeValue) {
  std::vector<long> params;
  for (const SurfaceProbe& p : probes) {
    if (p.patch != patch) continue;
    const float across = uEdge ? p.u : p.v, along = uEdge ? p.v : p.u;
    if (across == edgeValue) params.push_back(std::lround(along * 1e4));
  }
  std::sort(params.begin(), params.end());
  return params;
}

TEST_CASE("tessellation: neighbouring patches get equal levels on their shared edge (no cracks)") {
  test::glContext();
  auto renderer = test::makeRenderer();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> bump(-0.5, 0.5);
  std::vector<double> heights(64 * 64);
  for (double& h : heights) h = bump(rng);
  const int nx = 8, ny = 8;
  // A wavy graph seen in steep perspective, so edge lengths (and levels) vary a lot.
  const auto patches = test::graphPatches(
      [&](double x, double y) { return heights[size_t(std::lround(x + 20) * 64 + std::lround(y + 20))]; },
      nx, ny, -4.0, -4.0, 1.0);
  renderer->setPatches(patches);
  ViewParams view;
  view.eye = glm::dvec3(-1.0, -9.0, 2.5);
  view.view = glm::mat4(glm::lookAt(view.eye, glm::dvec3(0.0), glm::dvec3(0, 0, 1)));
  view.proj = glm::perspective(0.9f, 1.5f, 0.1f, 100.0f);
  view.viewport = {0, 0, 900, 600};
  for (float pixels : {3.0f, 7.0f, 20.0f}) {
    CAPTURE(pixels);
    ShadingParams shading;
    shading.tessPixels = pixels;
    const auto probes = renderer->probeSurface(view, shading);
    std::set<size_t> distinctCounts;
    int sharedEdges = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int k = j * nx + i;
        if (i + 1 < nx) {  // right neighbour: our u = 1 is its u = 0
          const auto mine = edgeParameters(probes, k, true, 1.0f);
          CHECK(mine == edgeParameters(probes, k + 1, true, 0.0f));
          distinctCounts.insert(mine.size());
          ++sharedEdges;
        }
        if (j + 1 < ny) {  // upper neighbour: our v = 1 is its v = 0
          const auto mine = edgeParameters(probes, k, false, 1.0f);
          CHECK(mine == edgeParameters(probes, k + nx, false, 0.0f));
          distinctCounts.insert(mine.size());
          ++sharedEdges;
        }
      }
    CHECK(sharedEdges == 2 * nx * (ny - 1));
    CHECK(distinctCounts.size() >= 3);  // the levels really are adaptive
  }
}

}  // namespace
}  // namespace polarview

namespace polarview {

TEST_CASE("gpu evaluator: neighbouring pole-cap sectors place their shared radial edge bit for bit alike") {
  // C2PS level 6 on the default model: 768 sectors, each drawn in its own rotated frame for K and H,
  // positioned from what the neighbours share (patch.tese): no pinholes between sub-pixel sectors.
  test::glContext();
  auto renderer = test::makeRenderer();
  const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  const PatchSet set = extractPatches(AdaptiveRefinement(mesh, RefineOptions{Scheme::C2PS, 6, false}));
  std::map<long, int> capOfSector;  // sector j -> patch index
  int n = 0;
  for (size_t k = 0; k < set.patches.size(); ++k)
    if (set.patches[k].kind == PatchKind::PoleCap && set.patches[k].pole == 0) {
      n = set.patches[k].sectorCount;
      capOfSector[set.patches[k].sector] = int(k);
    }
  REQUIRE(n == 768);
  REQUIRE(capOfSector.size() == size_t(n));
  renderer->setPatches(set.patches);
  const std::vector<SurfaceProbe> probes = renderer->probeSurface(4);
  std::map<std::pair<int, long>, glm::dvec3> atEdge;  // (patch, u * 1e4) -> position, on v = 0
  for (const SurfaceProbe& p : probes)
    if (p.v == 0.0f) atEdge[{p.patch, std::lround(p.u * 1e4)}] = p.position;
  size_t compared = 0, differ = 0;
  for (const SurfaceProbe& p : probes) {
    if (p.v != 1.0f || set.patches[size_t(p.patch)].kind != PatchKind::PoleCap) continue;
    const long j = set.patches[size_t(p.patch)].sector;
    const auto next = atEdge.find({capOfSector[(j + 1) % n], std::lround(p.u * 1e4)});
    if (next == atEdge.end()) continue;
    ++compared;
    differ += next->second != p.position;
  }
  MESSAGE(compared << " radial-edge vertices compared, " << differ << " differ");
  CHECK(compared >= size_t(n) * 4);
  CHECK(differ == 0);
}

}  // namespace polarview
