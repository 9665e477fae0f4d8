// The viewer's file loading and what a researcher reads off the views: drops through the GLFW drop
// callback, background loading that keeps the window drawing, the automatic colour range's
// percentiles, and pole rings that outline the pole without covering its colour.
//
#include <GLFW/glfw3.h>

#include "app_test_support.h"
#include "app/viewer_app.h"
#include "session/settings_rules.h"
#include "pipeline/surface_build.h"
#include "ui/viewer_panels.h"
#include "core/mesh/shapes.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

namespace polarview {
namespace {

namespace fs = std::filesystem;


// An open polar cap z = (x^2 - y^2) / 2 over `links` rings of `n` vertices (a saddle pole), as an
// OBJ file; returns its face count.
int writeSaddleObj(const fs::path& path, int n, int links) {
  std::ofstream out(path);
  out << "v 0 0 0\n";
  for (int k = 1; k <= links; ++k) {
    for (int j = 0; j < n; ++j) {
      double a = 2.0 * 3.14159265358979 * j / n, r = double(k) / links;
      double x = r * std::cos(a), y = r * std::sin(a);
      out << "v " << x << ' ' << y << ' ' << 0.5 * (x * x - y * y) << '\n';
    }
  }
  for (int j = 0; j < n; ++j) out << "f 1 " << 2 + j << ' ' << 2 + (j + 1) % n << '\n';
  for (int k = 1; k < links; ++k) {
    for (int j = 0; j < n; ++j) {
      int a = 2 + (k - 1) * n + j, b = 2 + (k - 1) * n + (j + 1) % n;
      out << "f " << a << ' ' << a + n << ' ' << b + n << ' ' << b << '\n';
    }
  }
  return n * links;
}


}  // namespace

TEST_CASE("drag and drop: a dropped OBJ replaces the model, a dropped bad file leaves it and shows why") {
  auto app = makeHiddenApp(480, 320);
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  const uint64_t start = app->modelGeneration();

  // The callback GLFW calls on a drop (read back by swapping it out and in again).
  GLFWdropfun drop = glfwSetDropCallback(app->window(), nullptr);
  glfwSetDropCallback(app->window(), drop);
  REQUIRE(bool(drop));

  fs::path good = fs::temp_directory_path() / "polarview_drop_saddle.obj";
  const int faces = writeSaddleObj(good, 6, 3);
  std::string goodPath = good.string();
  const char* goodPaths[] = {goodPath.c_str()};
  drop(app->window(), 1, goodPaths);
  app->waitUntilIdle();
  CHECK(app->modelGeneration() == start + 1);
  CHECK(app->status().file.loadedPath == goodPath);
  CHECK(app->status().file.modelFaces == faces);
  CHECK(app->status().file.error.empty());
  REQUIRE(app->shownSurface(0) != nullptr);
  CHECK(app->shownSurface(0)->key.model == app->modelGeneration());

  // A file with a face index past the vertices: refused with FILE:LINE, the saddle stays shown.
  fs::path bad = fs::temp_directory_path() / "polarview_drop_bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  std::string badPath = bad.string();
  const BuiltSurface* shown = app->shownSurface(0);
  const char* badPaths[] = {badPath.c_str(), goodPath.c_str()};  // only the first of several is opened
  drop(app->window(), 2, badPaths);
  app->waitUntilIdle();
  app->runFrame();
  CHECK(app->modelGeneration() == start + 1);
  CHECK(app->status().file.loadedPath == goodPath);
  CHECK(app->status().file.error.find("polarview_drop_bad.obj:4:") != std::string::npos);
  CHECK(app->shownSurface(0) == shown);
  fs::remove(good);
  fs::remove(bad);
}

TEST_CASE("model replacement: Ctrl+Z brings the previous model back (and again the replaced one)") {
  auto app = makeHiddenApp(480, 320);
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  const std::string defaultName = app->model().name;
  const int defaultFaces = app->status().file.modelFaces;
  CHECK(app->status().file.previousModelName.empty());

  fs::path saddle = fs::temp_directory_path() / "polarview_undo_saddle.obj";
  const int faces = writeSaddleObj(saddle, 6, 3);
  app->session().apply(app->document().requestLoad(saddle.string()));
  app->waitUntilIdle();
  REQUIRE(app->status().file.modelFaces == faces);
  CHECK(app->status().file.previousModelName == defaultName);

  // Ctrl+Z through the real key callback: the default model again, then the saddle (redo).
  GLFWkeyfun key = glfwSetKeyCallback(app->window(), nullptr);
  glfwSetKeyCallback(app->window(), key);
  REQUIRE(bool(key));
  auto ctrlZ = [&] {
    key(app->window(), GLFW_KEY_Z, 0, GLFW_PRESS, GLFW_MOD_CONTROL);
    key(app->window(), GLFW_KEY_Z, 0, GLFW_RELEASE, GLFW_MOD_CONTROL);
    app->runFrame();
    app->waitUntilIdle();
  };
  ctrlZ();
  CHECK(app->status().file.modelFaces == defaultFaces);
  CHECK(app->model().name == defaultName);
  REQUIRE(app->shownSurface(0) != nullptr);
  CHECK(app->shownSurface(0)->key.model == app->modelGeneration());
  ctrlZ();
  CHECK(app->status().file.modelFaces == faces);
  CHECK(app->status().file.loadedPath == saddle.string());
  fs::remove(saddle);
}

TEST_CASE("several dropped files: the first opens, the others are listed and PageDown / PageUp step through them") {
  auto app = makeHiddenApp(480, 320);
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  std::vector<std::string> paths;
  std::vector<int> faces;
  for (int n : {5, 7, 9}) {
    fs::path p = fs::temp_directory_path() / ("polarview_drop_list_" + std::to_string(n) + ".obj");
    faces.push_back(writeSaddleObj(p, n, 2));
    paths.push_back(p.string());
  }
  const char* raw[] = {paths[0].c_str(), paths[1].c_str(), paths[2].c_str()};
  GLFWdropfun drop = glfwSetDropCallback(app->window(), nullptr);
  glfwSetDropCallback(app->window(), drop);
  drop(app->window(), 3, raw);
  app->waitUntilIdle();
  CHECK(app->status().file.playlist == paths);
  CHECK(app->status().file.loadedPath == paths[0]);
  GLFWkeyfun key = glfwSetKeyCallback(app->window(), nullptr);
  glfwSetKeyCallback(app->window(), key);
  auto tap = [&](int k) {
    key(app->window(), k, 0, GLFW_PRESS, 0);
    key(app->window(), k, 0, GLFW_RELEASE, 0);
    app->runFrame();
    app->waitUntilIdle();
  };
  tap(GLFW_KEY_PAGE_DOWN);
  CHECK(app->status().file.loadedPath == paths[1]);
  CHECK(app->status().file.modelFaces == faces[1]);
  tap(GLFW_KEY_PAGE_DOWN);
  CHECK(app->status().file.loadedPath == paths[2]);
  tap(GLFW_KEY_PAGE_DOWN);  // wraps around
  CHECK(app->status().file.loadedPath == paths[0]);
  tap(GLFW_KEY_PAGE_UP);
  CHECK(app->status().file.loadedPath == paths[2]);
  for (const std::string& p : paths) fs::remove(p);
}

TEST_CASE("background loading: frames keep coming while a large OBJ loads, and the model changes only when it is ready") {
  auto app = makeHiddenApp(480, 320);
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  const uint64_t start = app->modelGeneration();
  const BuiltSurface* before = app->shownSurface(0);

  // 160k faces (some 10 MB): long enough to read that several frames pass meanwhile.
  fs::path big = fs::temp_directory_path() / "polarview_big_saddle.obj";
  const int faces = writeSaddleObj(big, 800, 200);
  app->session().apply(app->document().requestLoad(big.string()));
  int framesWhileLoading = 0;
  while (app->document().loading()) {
    app->runFrame();
    if (!app->document().loading()) break;
    ++framesWhileLoading;
    // Meanwhile the old model stays and the overlay says what is loading.
    CHECK(app->modelGeneration() == start);
    CHECK(app->shownSurface(0) == before);
    CHECK(app->status().file.loading);
  }
  MESSAGE("frames drawn while loading: " << framesWhileLoading);
  CHECK(framesWhileLoading >= 2);
  CHECK(app->modelGeneration() == start + 1);
  CHECK(app->status().file.modelFaces == faces);
  CHECK_FALSE(app->status().file.loading);

  // Requests while one runs: the last one wins.
  fs::path small = fs::temp_directory_path() / "polarview_small_saddle.obj";
  const int smallFaces = writeSaddleObj(small, 8, 2);
  app->session().apply(app->document().requestLoad(big.string()));
  app->session().apply(app->document().requestLoad((fs::temp_directory_path() / "polarview_no_such.obj").string()));
  app->session().apply(app->document().requestLoad(small.string()));
  app->waitUntilIdle();
  CHECK(app->status().file.loadedPath == small.string());
  CHECK(app->status().file.modelFaces == smallFaces);
  CHECK(app->status().file.error.empty());
  fs::remove(big);
  fs::remove(small);
}

TEST_CASE("asymmetric colour range: each side from its own percentile, switching automatic off keeps both") {
  auto app = makeHiddenApp(480, 320);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  settings.colour.symmetric = false;
  app->waitUntilIdle();
  app->runFrame();
  // The mushroom's K is mostly positive (cap) with a negative neck: two different sides.
  const double below = -colourInterval(settings, status).low, above = colourInterval(settings, status).high;
  CHECK(below > 0.0);
  CHECK(above > 0.0);
  CHECK(std::abs(below - above) > 0.1 * above);
  CHECK(std::max(below, above) == doctest::Approx(status.colour.sampled.symmetricRange));  // the symmetric one is the larger
  CHECK(status.colour.histogram.size() == size_t(kHistogramBins));
  CHECK(*std::max_element(status.colour.histogram.begin(), status.colour.histogram.end()) == 1.0f);
  setAutomaticRange(settings, status, false);
  CHECK(colourInterval(settings, status) == ColourInterval{-below, above});
}

TEST_CASE("pole rings: drawn around a visible pole without covering its colour, not drawn when the surface hides it") {
  auto app = makeHiddenApp(400, 400);
  app->session().apply(app->document().loadDefaultModel());  // the mushroom: one pole on top of the cap
  ViewerSettings& settings = app->settings();
  settings.showPanels = false;
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  app->waitUntilIdle();
  app->runFrame();

  auto differingPixels = [&](double pitch) {
    settings.sharedCamera.pitchDeg = pitch;
    settings.display.poleMarkers = true;
    RgbaImage with = app->renderImage(400, 400, 1, false);
    settings.display.poleMarkers = false;
    RgbaImage without = app->renderImage(400, 400, 1, false);
    std::vector<std::pair<int, int>> changed;
    for (int y = 0; y < 400; ++y) {
      for (int x = 0; x < 400; ++x) {
        if (!std::equal(with.at(x, y), with.at(x, y) + 3, without.at(x, y))) changed.emplace_back(x, y);
      }
    }
    return changed;
  };

  // From above the pole faces the camera: a ring of changed pixels, its centre untouched.
  std::vector<std::pair<int, int>> ring = differingPixels(60.0);
  REQUIRE(ring.size() > 20);
  double cx = 0, cy = 0;
  for (auto [x, y] : ring) {
    cx += x;
    cy += y;
  }
  cx /= double(ring.size());
  cy /= double(ring.size());
  for (auto [x, y] : ring) CHECK(std::hypot(x - cx, y - cy) < 12.0);
  for (auto [x, y] : ring) CHECK(std::hypot(x - cx, y - cy) > 3.0);

  // From below the cap hides its pole: nothing is drawn.
  CHECK(differingPixels(-70.0).empty());
}

}  // namespace polarview
