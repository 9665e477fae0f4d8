// Shared helpers of the render tests: one hidden GL context per process, small patch sets whose
// curvature is known in closed form, and cameras looking straight at them.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/spline/patch.h"
#include "render/framebuffer_capture.h"
#include "render/gl_context.h"
#include "render/patch_renderer.h"
#include "render/shader_library.h"

namespace polarview::test {

// The process-wide hidden context (tests run under xvfb-run); fails the test when unavailable.
inline HiddenGlContext& glContext() {
  static std::unique_ptr<HiddenGlContext> context;
  static std::string error;
  if (!context && error.empty()) {
    context = HiddenGlContext::create(64, 64, &error);
    if (context) MESSAGE("GL: " << context->versionString());
  }
  REQUIRE_MESSAGE(context, "no GL context: " << error);
  context->makeCurrent();
  return *context;
}

// One compiled shader library shared by all tests (compiling is slow on llvmpipe).
inline std::shared_ptr<ShaderLibrary> sharedShaders() {
  glContext();
  static std::shared_ptr<ShaderLibrary> library = std::make_shared<ShaderLibrary>();
  return library;
}

inline std::unique_ptr<PatchRenderer> makeRenderer() {
  auto renderer = std::make_unique<PatchRenderer>();
  std::string error;
  REQUIRE_MESSAGE(renderer->init(&error, sharedShaders()), error);
  return renderer;
}

// Graph z = f(x,y) as bicubic B-spline patches: control points (x_i, y_j, f(x_i, y_j)) on a grid of
// spacing h with cells [x0 + i h, x0 + (i+1) h] x ..., i < nx, j < ny. For a quadratic f the
// spline is exactly f + f_xx h^2/6 + f_yy h^2/6 over (x,y) (uniform B-splines reproduce quadratics
// up to that constant), so its curvature is the graph's.
inline std::vector<Patch> graphPatches(const std::function<double(double, double)>& f, int nx, int ny,
                                       double x0, double y0, double h,
                                       PatchKind kind = PatchKind::Regular) {
  std::vector<Patch> patches;
  for (int cj = 0; cj < ny; ++cj)
    for (int ci = 0; ci < nx; ++ci) {
      Patch patch;
      patch.kind = kind;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          const double x = x0 + (ci + i - 1) * h, y = y0 + (cj + j - 1) * h;
          patch.cp[4 * j + i] = Point(x, y, f(x, y));
        }
      patches.push_back(patch);
    }
  return patches;
}

// Gaussian and mean curvature of a graph z = f(x,y) with the upward normal (-f_x, -f_y, 1).
struct GraphCurvature {
  double gaussian, mean;
};
inline GraphCurvature graphCurvature(double fx, double fy, double fxx, double fyy, double fxy) {
  const double w = 1.0 + fx * fx + fy * fy;
  return {(fxx * fyy - fxy * fxy) / (w * w),
          ((1.0 + fx * fx) * fyy - 2.0 * fx * fy * fxy + (1.0 + fy * fy) * fxx) /
              (2.0 * std::pow(w, 1.5))};
}

// n PoleCap sectors (patch.h layout) of radius R with the Taylor expansion of the paraboloid
// z = x^2 + y^2 (K = 4, H = 2 at the pole; in the cap's radial unit, where the hole is
// r <= kPoleCapRadius: p1 = a e_x, p2 = a e_y, p3 = a^2 e_z, a = R / kPoleCapRadius) and a boundary
// B-spline through control points `boundaryScale` * T on the circle, zero first and second radial
// derivatives (any ring data: the u^3 blends keep the pole).
inline std::vector<Patch> paraboloidCap(int n, double R, double boundaryScale = 1.0,
                                        const Point& offset = Point(0.0)) {
  std::vector<Point> b(n);
  for (int j = 0; j < n; ++j) {
    const double t = 6.283185307179586 * j / n;
    const double x = boundaryScale * R * std::cos(t), y = boundaryScale * R * std::sin(t);
    b[j] = offset + Point(x, y, R * R);
  }
  const double a = R / kPoleCapRadius;
  std::vector<Patch> caps;
  for (int j = 0; j < n; ++j) {
    Patch patch;
    patch.kind = PatchKind::PoleCap;
    patch.ring = 0;
    patch.pole = 0;
    patch.sector = j;
    patch.sectorCount = n;
    patch.cp[0] = offset;
    patch.cp[1] = Point(a, 0, 0);
    patch.cp[2] = Point(0, a, 0);
    patch.cp[3] = Point(0, 0, a * a);
    for (int k = 0; k < 4; ++k) patch.cp[6 + k] = b[(j - 1 + k + n) % n];
    caps.push_back(patch);
  }
  return caps;
}

// Orthographic camera looking down -z at `center`, showing [-half, half]^2 around it.
inline ViewParams topView(const glm::dvec3& center, double half, glm::ivec4 viewport) {
  ViewParams view;
  view.eye = center + glm::dvec3(0, 0, 10.0 * half);
  view.view = glm::mat4(glm::lookAt(view.eye, center, glm::dvec3(0, 1, 0)));
  const float aspect = float(viewport.z) / float(viewport.w);
  view.proj = glm::ortho(-float(half) * aspect, float(half) * aspect, -float(half), float(half),
                         0.1f, 40.0f * float(half));
  view.viewport = viewport;
  return view;
}

// Flat curvature colours (no lighting) so pixels equal the map's colour.
inline ShadingParams flatCurvature(ShadingParams::Mode mode, ShadingParams::ColorMap map, float range) {
  ShadingParams shading;
  shading.mode = mode;
  shading.colormap = map;
  shading.range = ColourInterval::symmetric(range);
  shading.curvatureLighting = 0.0f;
  return shading;
}

inline DisplayFlags surfaceOnly() {
  DisplayFlags flags;
  flags.poleMarkers = false;
  return flags;
}

// Largest per-channel difference between a pixel and a [0,1] colour, in 8-bit steps.
inline int colorDistance(const uint8_t* pixel, const glm::vec3& color) {
  int worst = 0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(int(pixel[c]) - int(std::lround(color[c] * 255.0f))));
  return worst;
}

}  // namespace polarview::test
