// Orbit camera and view layout: properties over many random cameras, boxes and window sizes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec4.hpp>

#include "pipeline/orbit_camera.h"
#include "ui/viewer_panels.h"

using namespace polarview;

namespace {

OrbitCamera randomCamera(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  OrbitCamera c;
  c.target = {10 * u(rng), 10 * u(rng), 10 * u(rng)};
  c.distance = std::exp(3 * u(rng)) + 1e-3;
  c.yawDeg = 180 * u(rng);
  c.pitchDeg = 85 * u(rng);
  c.fovDeg = 47.5 + 42.5 * u(rng);
  return c;
}

}  // namespace

TEST_CASE("camera JSON: every camera survives a copy and paste exactly") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 500; ++trial) {
    OrbitCamera c = randomCamera(rng);
    std::string error;
    std::optional<OrbitCamera> back = cameraFromJson(cameraToJson(c), OrbitCamera{}, &error);
    REQUIRE_MESSAGE(back, error);
    CHECK(back->target == c.target);
    CHECK(back->distance == c.distance);
    CHECK(back->yawDeg == c.yawDeg);
    CHECK(back->pitchDeg == c.pitchDeg);
    CHECK(back->fovDeg == c.fovDeg);
  }
}

TEST_CASE("camera JSON: missing keys keep the base camera and malformed text is refused") {
  OrbitCamera base;
  base.distance = 7.0;
  std::string error;
  std::optional<OrbitCamera> partial = cameraFromJson(R"( { "yaw" : 12.5 } )", base, &error);
  REQUIRE(partial);
  CHECK(partial->yawDeg == 12.5);
  CHECK(partial->distance == 7.0);
  for (const char* bad : {"", "{", "{\"yaw\":}", "{\"yaw\":1,}", "{\"target\":[1,2]}", "{\"distance\":-1}",
                          "{\"fov\":180}", "{\"zoom\":1}", "{\"yaw\":nan}", "{\"yaw\":1} trailing", "[1,2,3]"}) {
    CAPTURE(bad);
    error.clear();
    CHECK_FALSE(cameraFromJson(bad, base, &error));
    CHECK_FALSE(error.empty());
  }
}

TEST_CASE("orbit camera: framing puts every corner of the box inside views of any aspect") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    OrbitCamera c = randomCamera(rng);
    glm::dvec3 lo{5 * u(rng), 5 * u(rng), 5 * u(rng)};
    glm::dvec3 hi = lo + glm::dvec3{std::exp(2 * u(rng)), std::exp(2 * u(rng)), std::exp(2 * u(rng))};
    double aspect = std::exp(1.5 * u(rng));
    c.frame(lo, hi, aspect);
    glm::mat4 clip = c.projectionMatrix(aspect, 0.5 * (lo + hi), 0.5 * glm::length(hi - lo)) * c.viewMatrix();
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
      glm::vec4 q = clip * glm::vec4(glm::vec3(p), 1.0f);
      CAPTURE(trial);
      CHECK(q.w > 0.0f);
      CHECK(std::abs(q.x / q.w) <= 1.0f);
      CHECK(std::abs(q.y / q.w) <= 1.0f);
      CHECK(std::abs(q.z / q.w) <= 1.0f);  // neither near- nor far-clipped
    }
  }
}

TEST_CASE("orbit camera: framing is tight: some corner of the box reaches the edge of the view") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    OrbitCamera c = randomCamera(rng);
    glm::dvec3 lo{5 * u(rng), 5 * u(rng), 5 * u(rng)};
    glm::dvec3 hi = lo + glm::dvec3{std::exp(2 * u(rng)), std::exp(2 * u(rng)), std::exp(2 * u(rng))};
    double aspect = std::exp(1.5 * u(rng));
    c.frame(lo, hi, aspect);
    glm::mat4 clip = c.projectionMatrix(aspect, 0.5 * (lo + hi), 0.5 * glm::length(hi - lo)) * c.viewMatrix();
    float widest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
      glm::vec4 q = clip * glm::vec4(glm::vec3(p), 1.0f);
      widest = std::max({widest, std::abs(q.x / q.w), std::abs(q.y / q.w)});
    }
    CAPTURE(trial);
    CHECK(widest > 0.9f);  // 1 / 1.08 = 0.926 unless the eye-distance floor applies
  }
}

TEST_CASE("orbit camera: framing below a title keeps every point in the middle fraction of the height, perspective and orthographic") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    OrbitCamera c = randomCamera(rng);
    c.orthographic = trial % 2 == 1;
    std::vector<glm::dvec3> points(20);
    for (glm::dvec3& p : points) p = {3 * u(rng), 3 * u(rng), 3 * u(rng)};
    const double aspect = std::exp(1.2 * u(rng)), fraction = 0.6 + 0.4 * std::abs(u(rng));
    c.framePoints(points.data(), points.size(), aspect, fraction);
    glm::mat4 clip = c.projectionMatrix(aspect, glm::dvec3(0.0), 6.0) * c.viewMatrix();
    float tallest = 0.0f;
    for (const glm::dvec3& p : points) {
      glm::vec4 q = clip * glm::vec4(glm::vec3(p), 1.0f);
      CAPTURE(trial);
      CHECK(q.w > 0.0f);
      CHECK(std::abs(q.x / q.w) <= 1.0f);
      CHECK(std::abs(q.y / q.w) <= float(fraction) + 1e-5f);
      CHECK(std::abs(q.z / q.w) <= 1.0f);
      tallest = std::max({tallest, std::abs(q.x / q.w), std::abs(q.y / q.w) / float(fraction)});
    }
    CHECK(tallest > 0.85f);  // still tight
  }
}

TEST_CASE("orbit camera: the wheel zooms towards the cursor: the point under it stays there") {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    OrbitCamera c = randomCamera(rng);
    c.orthographic = trial % 3 == 0;
    const double aspect = std::exp(u(rng)), ndcX = u(rng), ndcY = u(rng);
    // The point of the target's plane under the cursor.
    const double tanY = std::tan(glm::radians(c.fovDeg) / 2.0), tanX = aspect * tanY;
    const glm::dvec3 p = c.target + c.distance * (ndcX * tanX * c.right() + ndcY * tanY * c.up());
    const double before = c.distance;
    c.zoomAt(2.0 * u(rng), ndcX, ndcY, aspect);
    CHECK(c.distance != before);
    const glm::dmat4 clip = glm::dmat4(c.projectionMatrix(aspect, c.target, c.distance)) * glm::dmat4(c.viewMatrix());
    const glm::dvec4 q = clip * glm::dvec4(p, 1.0);
    CAPTURE(trial);
    CHECK(q.x / q.w == doctest::Approx(ndcX).epsilon(1e-4));
    CHECK(q.y / q.w == doctest::Approx(ndcY).epsilon(1e-4));
  }
}

TEST_CASE("orbit camera: zooming towards a surface point keeps it on screen and never passes it") {
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    OrbitCamera c = randomCamera(rng);
    const double aspect = std::exp(u(rng));
    // A point in front of the eye, somewhere in the view.
    const glm::dvec3 p = c.eye() + c.distance * (0.2 + std::abs(u(rng))) *
                                       (c.forward() + 0.3 * u(rng) * c.right() + 0.3 * u(rng) * c.up());
    auto ndc = [&] {  // the perspective projection in double (the camera's matrices are float)
      const glm::dvec3 d = p - c.eye();
      const double tanY = std::tan(glm::radians(c.fovDeg) / 2.0), depth = glm::dot(d, c.forward());
      return glm::dvec2(glm::dot(d, c.right()) / (depth * tanY * aspect), glm::dot(d, c.up()) / (depth * tanY));
    };
    const glm::dvec2 before = ndc();
    const glm::dvec3 forward = c.forward();
    for (int notch = 0; notch < 60; ++notch) c.zoomTowards(p, 1.0);
    const glm::dvec2 after = ndc();
    CAPTURE(trial);
    CHECK(after.x == doctest::Approx(before.x).epsilon(1e-6));
    CHECK(after.y == doctest::Approx(before.y).epsilon(1e-6));
    CHECK(glm::dot(p - c.eye(), forward) > 0.0);  // still in front after 60 notches
    CHECK(glm::length(c.forward() - forward) < 1e-12);  // the direction is kept
  }
}

TEST_CASE("orbit camera: the orthographic view shows at the target's depth what the perspective one shows") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    OrbitCamera c = randomCamera(rng);
    const double aspect = std::exp(u(rng));
    const glm::dvec3 p = c.target + c.distance * (0.3 * u(rng) * c.right() + 0.3 * u(rng) * c.up());
    auto project = [&](bool ortho) {
      c.orthographic = ortho;
      const glm::dvec4 q = glm::dmat4(c.projectionMatrix(aspect, c.target, c.distance)) * glm::dmat4(c.viewMatrix()) * glm::dvec4(p, 1.0);
      return glm::dvec2(q.x / q.w, q.y / q.w);
    };
    const glm::dvec2 a = project(false), b = project(true);
    CAPTURE(trial);
    CHECK(a.x == doctest::Approx(b.x).epsilon(1e-4));
    CHECK(a.y == doctest::Approx(b.y).epsilon(1e-4));
  }
  // The projection travels with the camera JSON.
  OrbitCamera ortho;
  ortho.orthographic = true;
  std::string error;
  auto back = cameraFromJson(cameraToJson(ortho), OrbitCamera{}, &error);
  REQUIRE_MESSAGE(back, error);
  CHECK(back->orthographic);
  CHECK(!cameraFromJson("{\"ortho\":2}", OrbitCamera{}, &error));
}

TEST_CASE("orbit camera: setting the pivot keeps the eye and looks at the new point") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    OrbitCamera c = randomCamera(rng);
    glm::dvec3 eye = c.eye();
    // A point in front of the camera, not too close to straight up or down.
    glm::dvec3 point = eye + c.distance * (c.forward() + 0.3 * u(rng) * c.right() + 0.3 * u(rng) * c.up());
    c.setPivotKeepingEye(point);
    CHECK(glm::length(c.eye() - eye) < 1e-9 * (1.0 + glm::length(eye)));
    CHECK(glm::length(c.target - point) < 1e-12 * (1.0 + glm::length(point)));
  }
}

TEST_CASE("orbit camera: orbiting and panning keep the screen axes orthonormal and +z up") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    OrbitCamera c = randomCamera(rng);
    c.orbit(500 * u(rng), 500 * u(rng));
    glm::dvec3 targetBefore = c.target;
    double distanceBefore = c.distance;
    c.pan(200 * u(rng), 200 * u(rng), 600);
    CHECK(std::abs(glm::dot(c.target - targetBefore, c.forward())) < 1e-9 * (1 + distanceBefore));  // pans in the screen plane
    CHECK(std::abs(glm::length(c.right()) - 1) < 1e-12);
    CHECK(std::abs(glm::length(c.up()) - 1) < 1e-12);
    CHECK(std::abs(glm::dot(c.right(), c.forward())) < 1e-12);
    CHECK(c.up().z >= 0.0);
    CHECK(std::abs(c.pitchDeg) <= 89.0);
  }
}

TEST_CASE("view layout: the views tile the frame above the colour bar without gaps or overlaps") {
  for (int count = 1; count <= kMaxViews; ++count) {
    for (float width : {100.0f, 641.0f, 1230.0f, 1600.0f, 3000.0f}) {
      for (float height : {90.0f, 500.0f, 900.0f, 2000.0f}) {
        CAPTURE(count);
        CAPTURE(width);
        CAPTURE(height);
        ScreenRect frame{370, 0, width, height};
        std::vector<ScreenRect> views = layoutViews(count, frame, 64);
        REQUIRE(int(views.size()) == count);
        // Areas add up to the frame above the strip (integer edges) and no two views overlap.
        double area = 0.0;
        for (const ScreenRect& r : views) {
          area += double(r.w) * r.h;
          CHECK(r.x >= frame.x);
          CHECK(r.x + r.w <= frame.x + width);
          CHECK(r.y >= 0.0f);
          CHECK(r.y + r.h <= std::max(height - 64, 1.0f));
        }
        CHECK(std::abs(area - double(std::floor(frame.x + width) - frame.x) * std::floor(std::max(height - 64, 1.0f))) < 1.0);
        for (size_t a = 0; a < views.size(); ++a) {
          for (size_t b = a + 1; b < views.size(); ++b) {
            float overlapX = std::min(views[a].x + views[a].w, views[b].x + views[b].w) - std::max(views[a].x, views[b].x);
            float overlapY = std::min(views[a].y + views[a].h, views[b].y + views[b].h) - std::max(views[a].y, views[b].y);
            CHECK_FALSE((overlapX > 0 && overlapY > 0));
          }
        }
        // All views are the same size to within a pixel.
        for (const ScreenRect& r : views) {
          CHECK(std::abs(r.w - views[0].w) <= 1.0f);
          CHECK(std::abs(r.h - views[0].h) <= 1.0f);
        }
      }
    }
  }
}

TEST_CASE("view layout: views stay side by side in a wide frame and form a 2 x 2 grid in a 16:9 one") {
  std::vector<ScreenRect> wide = layoutViews(4, ScreenRect{0, 0, 1600, 400}, 0);
  for (const ScreenRect& r : wide) CHECK(r.y == 0.0f);
  std::vector<ScreenRect> grid = layoutViews(4, ScreenRect{0, 0, 1230, 900}, 64);
  CHECK(grid[1].y == 0.0f);
  CHECK(grid[2].y > 0.0f);
  CHECK(grid[2].x == grid[0].x);
}

