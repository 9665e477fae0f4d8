// The viewer application driven frame by frame in a hidden window: it keeps its model through bad
// files, ends on the last of many quick scheme/level changes, survives resizes and a valence-1024
// pole, refuses levels over the budget, and writes screenshots with labels and the colour bar.
//
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app_test_support.h"
#include "app/viewer_app.h"
#include "session/settings_rules.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"
#include "core/spline/patch_extraction.h"
#include "pipeline/eigen_nets.h"
#include "render/patch_renderer.h"
#include "pipeline/pole_inspection.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/adaptive_refiner.h"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <thread>
#include <chrono>

#include <stb_image.h>

namespace polarview {
namespace {

namespace fs = std::filesystem;


void runFrames(ViewerApp& app, int frames) {
  for (int f = 0; f < frames; ++f) app.runFrame();
}

// A shown surface equals what the settings ask for.
bool showsWanted(const ViewerApp& app, int v) {
  const BuiltSurface* shown = app.shownSurface(v);
  const View& wanted = app.settings().views[size_t(v)];
  return shown && shown->key.model == app.modelGeneration() && shown->key.scheme == wanted.scheme &&
         shown->key.level == wanted.level;
}

// An open valence-n cap: pole, one link of n 4-valent vertices, a boundary link; z = r^2 / 2.
PolyMesh fanWithOneRing(int n) {
  PolyMesh mesh;
  mesh.points.push_back({0, 0, 0});
  for (int ring = 1; ring <= 2; ++ring) {
    for (int j = 0; j < n; ++j) {
      double a = 2.0 * 3.14159265358979 * j / n, r = ring;
      mesh.points.push_back({r * std::cos(a), r * std::sin(a), 0.5 * r * r});
    }
  }
  auto q = [n](int ring, int j) { return Index(1 + (ring - 1) * n + (j % n)); };
  for (int j = 0; j < n; ++j) mesh.addFace({0, q(1, j), q(1, j + 1)});
  for (int j = 0; j < n; ++j) mesh.addFace({q(1, j), q(2, j), q(2, j + 1), q(1, j + 1)});
  return mesh;
}

bool near(const uint8_t* pixel, const glm::vec3& colour, int tolerance) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(int(pixel[c]) - int(std::lround(colour[c] * 255.0f))) > tolerance) return false;
  }
  return true;
}

std::pair<int, int> pngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), 24);
  auto be32 = [&](int at) { return int(header[at]) << 24 | int(header[at + 1]) << 16 | int(header[at + 2]) << 8 | int(header[at + 3]); };
  return {be32(16), be32(20)};
}

// Alt+click at the fractions (fx, fy) of view 0 (the readout lands in state().readout); checks
// that `drawn` (the read point as the view draws it) projects back under the cursor.
const PointReadout& altClickReadout(ViewerApp& app, float fx, float fy, const std::function<Point(const Point&)>& drawn) {
  const ViewTransform view = app.viewTransform(0);
  const float x = view.rect.x + fx * view.rect.w, y = view.rect.y + fy * view.rect.h;
  app.requestPivot(PivotPick{0, x, y, 0.0f, true, false});
  app.runFrame();
  REQUIRE(app.status().readout.valid);
  const PointReadout& r = app.status().readout.readout;
  const auto at = view.project(drawn(r.point.position));
  REQUIRE(at);
  CHECK(std::abs(at->x - x) < 1.5);
  CHECK(std::abs(at->y - y) < 1.5);
  return r;
}

}  // namespace

TEST_CASE("viewer app: a file that fails to load leaves the model shown and the error in the state") {
  auto app = makeHiddenApp();
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  REQUIRE(showsWanted(*app, 0));
  const uint64_t generation = app->modelGeneration();
  const BuiltSurface* before = app->shownSurface(0);

  fs::path bad = fs::temp_directory_path() / "polarview_app_test_bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  CHECK_FALSE(app->session().apply(app->document().loadFile(bad.string())));
  CHECK(app->status().file.error.find("polarview_app_test_bad.obj:4:") != std::string::npos);

  // The same through the file panel's request, with a file that does not exist.
  app->settings().file.pathField = (fs::temp_directory_path() / "polarview_no_such_file.obj").string();
  app->session().queueCommand("file.open");
  runFrames(*app, 1);    // takes the request: the file is read in the background
  app->waitUntilIdle();
  runFrames(*app, 1);
  CHECK(app->status().file.error.find("polarview_no_such_file.obj") != std::string::npos);
  CHECK(app->modelGeneration() == generation);
  CHECK(app->shownSurface(0) == before);
  fs::remove(bad);
}

TEST_CASE("viewer app: after many quick scheme and level changes every view shows the last request") {
  auto app = makeHiddenApp();
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.viewCount = 3;
  settings.linkLevels = false;
  std::mt19937 rng(42);
  for (int frame = 0; frame < 40; ++frame) {
    int v = int(rng() % 3);
    settings.views[size_t(v)].scheme = static_cast<SchemeChoice>(rng() % kSchemeChoiceCount);
    settings.views[size_t(v)].level = int(rng() % 4);
    if (frame % 7 == 0) settings.viewCount = 1 + int(rng() % 3);
    app->runFrame();
  }
  settings.viewCount = 3;
  app->waitUntilIdle();
  runFrames(*app, 2);
  for (int v = 0; v < 3; ++v) {
    CAPTURE(v);
    REQUIRE(showsWanted(*app, v));
    // What is shown is what a fresh build of the same key gives.
    auto fresh = buildSurface(app->model(), app->shownSurface(v)->key, kDefaultFaceBudget);
    CHECK(status.views[size_t(v)].patchCount == int(fresh->patches.size()));
    int sum = 0;
    for (int count : status.views[size_t(v)].patchesPerKind) sum += count;
    CHECK(sum == status.views[size_t(v)].patchCount);
  }
}

TEST_CASE("viewer app: resizing the window keeps every view drawn at the new size") {
  auto app = makeHiddenApp(640, 400);
  app->session().apply(app->document().loadDefaultModel());
  app->settings().viewCount = 2;
  app->waitUntilIdle();
  for (auto [w, h] : {std::pair{800, 300}, std::pair{300, 500}, std::pair{1000, 700}, std::pair{200, 150}}) {
    CAPTURE(w);
    glfwSetWindowSize(app->window(), w, h);
    runFrames(*app, 3);
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(app->window(), &fw, &fh);
    CHECK(fw == w);
    CHECK(fh == h);
    CHECK(ImGui::GetIO().DisplaySize.x == float(w));
    // Each view's centre shows the model, not the background.
    RgbaImage image = app->renderImage(fw, fh, 1, false);
    REQUIRE(image.width == fw);
    std::vector<ScreenRect> views = layoutViews(2, ScreenRect{0, 0, float(fw), float(fh)}, colourBarReserve(app->settings(), 1.0f));
    for (const ScreenRect& r : views) {
      const uint8_t* centre = image.at(int(r.x + r.w / 2), int(r.y + r.h / 2));
      CHECK_FALSE(near(centre, glm::vec3(kBackground[0], kBackground[1], kBackground[2]), 2));
    }
  }
}

TEST_CASE("viewer app: a valence-1024 pole is refined, drawn and the app keeps running") {
  auto app = makeHiddenApp();
  REQUIRE(app->session().apply(app->document().loadMesh(fanWithOneRing(1024), "fan-1024")));
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.viewCount = 2;
  settings.views[1].scheme = SchemeChoice::CatmullClark;
  for (int level = 0; level <= 2; ++level) {
    CAPTURE(level);
    requestLevel(settings, status, app->notices(), level);
    app->waitUntilIdle();
    runFrames(*app, 2);
    for (int v = 0; v < 2; ++v) {
      // Either the level is shown, or it was refused / failed with a message and the app goes on.
      CHECK((showsWanted(*app, v) || !status.views[size_t(v)].message.empty()));
    }
    CHECK(status.frameMs > 0.0);
  }
  CHECK(app->shownSurface(0) != nullptr);
}

TEST_CASE("viewer app: a level over the face budget is refused with a message and the view keeps its level") {
  auto app = makeHiddenApp(640, 400, 20000);
  app->session().apply(app->document().loadDefaultModel());
  requestLevel(app->settings(), app->status(), app->notices(), 1);
  app->waitUntilIdle();
  REQUIRE(showsWanted(*app, 0));
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  // One limit: the slider's range, the keys' refusal and the app's refusal agree.
  const int deepest = deepestLevel(app->model(), SchemeChoice::C2PS, 20000);
  CHECK(status.views[0].deepestLevel == deepest);
  CHECK(deepest >= 1);
  CHECK(deepest < 8);
  requestLevel(settings, status, app->notices(), 8);  // a key or the slider: refused at once, nothing changes
  CHECK(settings.views[0].level == 1);
  CHECK(app->notices().text().find("level 8 refused: C2PS stops at level " + std::to_string(deepest)) == 0);
  requestLevel(settings, status, app->notices(), deepest);  // a level within reach clears the stale refusal
  CHECK(app->notices().text().empty());
  CHECK(settings.views[0].level == deepest);
  app->waitUntilIdle();
  settings.views[0].level = 8;  // set directly (as `view --level` does): the app refuses it
  app->waitUntilIdle();
  runFrames(*app, 2);
  CHECK(status.views[0].message.find("level 8 refused: C2PS stops at level " + std::to_string(deepest)) == 0);
  CHECK(status.views[0].message == levelRefusal(app->model(), SchemeChoice::C2PS, 8, 20000));
  CHECK(settings.views[0].level == deepest);
  CHECK(app->shownSurface(0)->key.level == deepest);
}

TEST_CASE("viewer app: screenshots are numbered PNGs of the view area with labels and the colour bar") {
  auto app = makeHiddenApp(720, 360);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  settings.viewCount = 2;
  settings.views[1].scheme = SchemeChoice::CatmullClark;
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  settings.colour.automatic = false;
  settings.colour.typedRange = 0.5f;
  app->waitUntilIdle();
  runFrames(*app, 2);

  fs::path previous = fs::current_path();
  fs::path dir = fs::temp_directory_path() / "polarview_app_screens";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::current_path(dir);
  settings.screenshot.supersample = 2;
  std::string first = app->saveScreenshot();
  std::string second = app->saveScreenshot();
  fs::current_path(previous);
  CHECK(fs::path(first).filename() == "polarview_0001.png");
  CHECK(fs::path(second).filename() == "polarview_0002.png");
  const ScreenRect area = app->viewArea();  // the window less the panel column
  CHECK(pngSize(first) == std::pair{int(area.w), int(area.h)});

  // The colour bar: both ends of the map appear in the strip under the views.
  RgbaImage image = app->renderImage(720, 360, 1, false);
  const float reserve = colourBarReserve(settings, 1.0f);
  bool low = false, high = false;
  for (int y = int(360 - reserve); y < 360; ++y) {
    for (int x = 0; x < 720; ++x) {
      low = low || near(image.at(x, y), colorMapCpu(settings.shading.colormap, -0.5f, 0.5f), 6);
      high = high || near(image.at(x, y), colorMapCpu(settings.shading.colormap, 0.5f, 0.5f), 6);
    }
  }
  CHECK(low);
  CHECK(high);
  // The labels: white text at the top of each view.
  for (const ScreenRect& r : layoutViews(2, ScreenRect{0, 0, 720, 360}, reserve)) {
    int white = 0;
    for (int y = 4; y < 32; ++y) {
      for (int x = int(r.x + r.w / 3); x < int(r.x + 2 * r.w / 3); ++x) white += near(image.at(x, y), glm::vec3(1.0f), 20);
    }
    CHECK(white > 15);
  }
  fs::remove_all(dir);
}

TEST_CASE("viewer app: the X screenshot shows the views exactly as the window does (4 views in a 2 x 2 grid)") {
  auto app = makeHiddenApp(1280, 720);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  settings.viewCount = 4;
  settings.views[1].scheme = SchemeChoice::RTS;
  settings.views[2].scheme = SchemeChoice::BPS;
  settings.views[3].scheme = SchemeChoice::CatmullClark;
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  app->session().queueCommand("camera.frame");
  app->waitUntilIdle();
  runFrames(*app, 2);

  fs::path dir = fs::temp_directory_path() / "polarview_app_layout";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string windowPng = (dir / "window.png").string();
  app->captureWindowNextFrame(windowPng);
  app->runFrame();
  fs::path previous = fs::current_path();
  fs::current_path(dir);
  settings.screenshot.supersample = 1;
  const std::string shot = app->saveScreenshot();
  fs::current_path(previous);
  REQUIRE(!shot.empty());

  int ww = 0, wh = 0, sw = 0, sh = 0, channels = 0;
  uint8_t* window = stbi_load(windowPng.c_str(), &ww, &wh, &channels, 4);
  uint8_t* image = stbi_load(shot.c_str(), &sw, &sh, &channels, 4);
  REQUIRE(window);
  REQUIRE(image);
  const ScreenRect area = app->viewArea();
  CHECK(sw == int(area.w));
  CHECK(sh == int(area.h));
  CHECK(layoutViews(4, area, colourBarReserve(settings, 1.0f))[2].y > 0.0f);  // 2 x 2 on screen
  // The screenshot is the window's view area pixel for pixel, up to rounding.
  int differing = 0;
  for (int y = 0; y < std::min(sh, wh); ++y)
    for (int x = 0; x < sw && x + int(area.x) < ww; ++x) {
      const uint8_t* a = image + 4 * (size_t(y) * sw + x);
      const uint8_t* b = window + 4 * (size_t(y) * ww + x + int(area.x));
      int worst = 0;
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a[c]) - int(b[c])));
      differing += worst > 12;
    }
  stbi_image_free(window);
  stbi_image_free(image);
  MESSAGE("screenshot " << sw << "x" << sh << ": " << differing << " pixels differ from the window's view area");
  CHECK(differing < sw * sh / 200);
  fs::remove_all(dir);
}

TEST_CASE("viewer app: every key press counts, even several within one frame") {
  auto app = makeHiddenApp(640, 400);
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  runFrames(*app, 2);
  // The callback GLFW calls on a key event (ImGui's, which chains to the app's).
  GLFWkeyfun key = glfwSetKeyCallback(app->window(), nullptr);
  glfwSetKeyCallback(app->window(), key);
  REQUIRE(bool(key));
  auto tap = [&](int k, int mods = 0) {
    key(app->window(), k, 0, GLFW_PRESS, mods);
    key(app->window(), k, 0, GLFW_RELEASE, mods);
  };
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  const int map = int(settings.shading.colormap), views = settings.viewCount;
  // Three quick C presses and a V, all released before the next frame polls the keyboard.
  tap(GLFW_KEY_C);
  tap(GLFW_KEY_C);
  tap(GLFW_KEY_C);
  tap(GLFW_KEY_V);
  app->runFrame();
  CHECK(int(settings.shading.colormap) == (map + 3) % 4);
  CHECK(settings.viewCount == views % kMaxViews + 1);
  // Modifiers travel with the press: Shift+S steps the scheme back, S forward again.
  const SchemeChoice scheme = settings.views[size_t(settings.activeView)].scheme;
  tap(GLFW_KEY_S, GLFW_MOD_SHIFT);
  app->runFrame();
  CHECK(settings.views[size_t(settings.activeView)].scheme != scheme);
  tap(GLFW_KEY_S);
  app->runFrame();
  CHECK(settings.views[size_t(settings.activeView)].scheme == scheme);
  // A: automatic range off keeps the range on screen (it used to jump to +-1).
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  app->runFrame();
  REQUIRE(settings.colour.automatic);
  const ColourInterval range = colourInterval(settings, status);
  CHECK(range.high != 1.0f);
  tap(GLFW_KEY_A);
  app->runFrame();
  CHECK(!settings.colour.automatic);
  CHECK(colourInterval(settings, status) == range);
  // A press during a slow frame (no frame in between) still sets the level.
  tap(GLFW_KEY_2);
  app->runFrame();
  CHECK(settings.views[0].level == 2);
}

TEST_CASE("viewer app: RTS and BPS at a valence-4 pole say in the title and stats that Catmull-Clark refined it") {
  auto app = makeHiddenApp(640, 400);
  REQUIRE(app->session().apply(app->document().loadMesh(fanWithOneRing(4), "valence-4 fan")));
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.viewCount = 3;
  settings.views[0].scheme = SchemeChoice::RTS;
  settings.views[1].scheme = SchemeChoice::BPS;
  settings.views[2].scheme = SchemeChoice::C2PS;
  for (View& view : settings.views) view.level = 2;
  app->waitUntilIdle();
  runFrames(*app, 1);
  for (int v = 0; v < 2; ++v) {
    CAPTURE(v);
    CHECK(status.views[v].polesByScheme == 0);
    CHECK(status.views[v].polesByCatmullClark == 1);
    CHECK(status.views[v].fallbackReason.find("valence >= 5") != std::string::npos);
    CHECK(viewTitle(status.views[v]).find("poles by CC") != std::string::npos);
  }
  CHECK(viewTitle(status.views[0]).rfind("RTS", 0) == 0);
  // C2PS refines any valence >= 3: a plain title.
  CHECK(status.views[2].polesByScheme == 1);
  CHECK(status.views[2].polesByCatmullClark == 0);
  CHECK(viewTitle(status.views[2]) == "C2PS \xC2\xB7 2");
  // Valence 6: RTS refines it.
  REQUIRE(app->session().apply(app->document().loadMesh(fanWithOneRing(6), "valence-6 fan")));
  app->waitUntilIdle();
  runFrames(*app, 1);
  CHECK(status.views[0].polesByScheme == 1);
  CHECK(viewTitle(status.views[0]) == "RTS \xC2\xB7 2");
}

TEST_CASE("viewer app: adding views, hiding the panels or resizing re-frames, a preset shows the whole model again") {
  auto app = makeHiddenApp(1280, 720);
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  runFrames(*app, 1);
  ViewerSettings& settings = app->settings();
  const double one = settings.sharedCamera.distance;
  settings.viewCount = 4;  // 2 x 2: each view is smaller and closer to square
  runFrames(*app, 1);
  const double four = settings.sharedCamera.distance;
  CHECK(four != one);
  settings.showPanels = false;
  runFrames(*app, 1);
  CHECK(settings.sharedCamera.distance != four);
  // A close-up, then F2: the top view of the whole model, not of the close-up.
  settings.showPanels = true;
  runFrames(*app, 1);
  const double framed = settings.sharedCamera.distance;
  settings.sharedCamera.zoom(12.0);
  app->session().queueCommand("camera.top");
  runFrames(*app, 1);
  CHECK(settings.sharedCamera.pitchDeg > 80.0);
  CHECK(settings.sharedCamera.distance > 0.5 * framed);
}

TEST_CASE("viewer app: F during a pole zoom frames the zoomed rings, and they are drawn") {
  auto app = makeHiddenApp(800, 600);
  REQUIRE(app->session().apply(app->document().loadMesh(shapes::globe(8, 5), "globe")));
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[0].level = 3;
  app->waitUntilIdle();
  runFrames(*app, 1);
  const double whole = settings.sharedCamera.distance;
  const glm::dvec3 wholeTarget = settings.sharedCamera.target;
  // Ring 4 at level 3: the level goes to 6 (the rings 4..6 were missing: a blank view).
  settings.poleInspector.zoomRing = 4;
  runFrames(*app, 1);
  app->waitUntilIdle();
  runFrames(*app, 2);
  REQUIRE(status.views[0].shownLevel == 6);
  CHECK(status.views[0].zoomRing == 4);
  app->session().queueCommand("camera.frame");
  runFrames(*app, 1);
  // Rings 4..6 scaled by 2^4 about one pole reach out as far as rings 0..2: larger than the model
  // (they filled the view), framed about the pole.
  CHECK(settings.sharedCamera.distance > 1.2 * whole);
  CHECK(glm::length(settings.sharedCamera.target - wholeTarget) > 0.3);
  // Off again: F frames the model.
  settings.poleInspector.zoomRing = -1;
  runFrames(*app, 1);
  app->session().queueCommand("camera.frame");
  runFrames(*app, 1);
  CHECK(settings.sharedCamera.distance == doctest::Approx(whole));
}

TEST_CASE("viewer app: Ctrl+C / Ctrl+V copy the camera to the clipboard as JSON and back") {
  auto app = makeHiddenApp();
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  ViewerSettings& settings = app->settings();
  settings.sharedCamera.yawDeg = 33.25;
  settings.sharedCamera.pitchDeg = -12.5;
  const OrbitCamera copied = settings.sharedCamera;
  app->session().queueCommand("camera.copy");
  runFrames(*app, 1);
  const char* clipboard = glfwGetClipboardString(app->window());
  REQUIRE(clipboard != nullptr);
  CHECK(std::string(clipboard) == cameraToJson(copied));
  settings.sharedCamera.orbit(200, 100);
  settings.sharedCamera.zoom(3);
  app->session().queueCommand("camera.paste");
  runFrames(*app, 1);
  CHECK(cameraToJson(settings.sharedCamera) == cameraToJson(copied));
}

TEST_CASE("viewer app: a double-click on the surface moves the pivot onto it and keeps the eye") {
  auto app = makeHiddenApp(600, 600);
  app->settings().showPanels = false;
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  runFrames(*app, 2);
  const glm::dvec3 eye = app->settings().sharedCamera.eye();
  const glm::dvec3 oldTarget = app->settings().sharedCamera.target;
  // A point a little off the centre of the only view, on the mushroom's cap.
  app->requestPivot(PivotPick{0, 300.0f, 230.0f});
  runFrames(*app, 1);
  const OrbitCamera& camera = app->settings().sharedCamera;
  CAPTURE(app->notices().text());
  CHECK(glm::length(camera.eye() - eye) < 1e-4 * glm::length(eye));
  CHECK(glm::length(camera.target - oldTarget) > 1e-3);
  // The new pivot is a surface point: inside the model's box (up to the limit surface's shrinkage).
  for (int axis = 0; axis < 3; ++axis) {
    CHECK(camera.target[axis] >= app->document().modelMin()[axis] - 1e-3);
    CHECK(camera.target[axis] <= app->document().modelMax()[axis] + 1e-3);
  }
  // Background under the cursor leaves the camera alone.
  const OrbitCamera before = camera;
  app->requestPivot(PivotPick{0, 5.0f, 5.0f});
  runFrames(*app, 1);
  CHECK(cameraToJson(app->settings().sharedCamera) == cameraToJson(before));
}


TEST_CASE("level keys: ] and [ step the level past 9 and stop at the model's limit") {
  auto app = makeHiddenApp();
  app->session().apply(app->document().loadDefaultModel());
  app->waitUntilIdle();
  GLFWkeyfun key = glfwSetKeyCallback(app->window(), nullptr);
  glfwSetKeyCallback(app->window(), key);
  REQUIRE(bool(key));
  auto tap = [&](int k) {
    key(app->window(), k, 0, GLFW_PRESS, 0);
    key(app->window(), k, 0, GLFW_RELEASE, 0);
    app->runFrame();
  };
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[0].scheme = SchemeChoice::BPS;
  app->runFrame();  // the status (deepest level) follows the scheme
  requestLevel(settings, status, app->notices(), 9);
  for (int k = 0; k < 3; ++k) tap(GLFW_KEY_RIGHT_BRACKET);
  CHECK(settings.views[0].level == 12);
  tap(GLFW_KEY_LEFT_BRACKET);
  CHECK(settings.views[0].level == 11);
  const int deepest = status.views[0].deepestLevel;
  REQUIRE(deepest >= 12);
  requestLevel(settings, status, app->notices(), deepest);
  tap(GLFW_KEY_RIGHT_BRACKET);
  CHECK(settings.views[0].level == deepest);
  CHECK(app->notices().text().find("refused") != std::string::npos);
}

TEST_CASE("viewer app: level steps reuse the view's refinement, the next level is made ahead, and what is shown equals a fresh build") {
  auto app = makeHiddenApp(640, 400, kDefaultFaceBudget, /*prepareNextLevel=*/true);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.viewCount = 2;
  settings.linkLevels = false;
  settings.views[0].scheme = SchemeChoice::C2PS;
  settings.views[1].scheme = SchemeChoice::RTS;
  settings.views[0].level = settings.views[1].level = 2;
  app->waitUntilIdle();
  runFrames(*app, 1);
  const AdaptiveRefinement* refinement = app->shownSurface(0)->refinement.get();
  int previous = 2;
  for (int level : {3, 4, 2, 5, 4, 5}) {
    CAPTURE(level);
    settings.views[0].level = settings.views[1].level = level;
    app->waitUntilIdle();
    runFrames(*app, 1);
    REQUIRE(showsWanted(*app, 0));
    const BuiltSurface& shown = *app->shownSurface(0);
    CHECK(shown.refinement.get() == refinement);  // one refinement, stepped
    // Made ahead while idle: the next level is there before it is asked for, in the active view
    // its whole surface, which a step up hands out with nothing to assemble.
    CHECK(shown.hierarchy->deepestMade.load() >= level + 1);
    // (After a step down from level + 1 the view keeps that surface instead: nothing made ahead.)
    if (previous != level + 1) CHECK(shown.hierarchy->aheadLevel.load() == level + 1);
    if (level == previous + 1) CHECK(status.views[0].patchesMs == 0.0);
    previous = level;
    CHECK(status.views[0].keptPatches > 0);  // regular patches of shared levels stayed on the GPU
    for (int v = 0; v < 2; ++v) {
      const BuiltSurface& surface = *app->shownSurface(v);
      // RTS is not C2 at the pole: its holes are closed at kNonC2CapLevel whatever the level asked.
      CHECK(surface.patchLevel == (v == 0 ? level : kNonC2CapLevel));
      const PatchSet fresh =
          extractPatches(AdaptiveRefinement(*app->model().mesh, refineOptionsFor(surface.key.scheme, surface.patchLevel)));
      REQUIRE(fresh.patches.size() == surface.patches.size());
      size_t differ = 0;
      for (size_t k = 0; k < fresh.patches.size(); ++k)
        differ += fresh.patches[k].cp != surface.patches[k].cp || fresh.patches[k].edgeLevelDelta != surface.patches[k].edgeLevelDelta;
      CHECK(differ == 0);
    }
  }
}

TEST_CASE("viewer app: a step back to the level shown before shows its surface again, nothing built; not across a scheme change") {
  auto app = makeHiddenApp(640, 400, kDefaultFaceBudget, /*prepareNextLevel=*/true);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[0].scheme = SchemeChoice::C2PS;
  auto step = [&](int level) {
    settings.views[0].level = level;
    app->runFrame();
    app->waitUntilIdle();
    app->runFrame();
    REQUIRE(showsWanted(*app, 0));
  };
  step(5);
  const BuiltSurface* five = app->shownSurface(0);
  step(6);
  const BuiltSurface* six = app->shownSurface(0);
  CHECK_FALSE(status.views[0].reshown);
  step(5);
  CHECK(app->shownSurface(0) == five);
  CHECK(status.views[0].reshown);
  CHECK(status.views[0].keptPatches > 0);
  CHECK(app->renderer(0).patchCount() == int(five->patches.size()));
  step(6);
  CHECK(app->shownSurface(0) == six);  // and forth again
  CHECK(status.views[0].reshown);

  // Another scheme between: the kept level is of the old scheme, so it goes.
  settings.views[0].scheme = SchemeChoice::RTS;
  step(6);
  settings.views[0].scheme = SchemeChoice::C2PS;
  step(6);  // the parked C2PS 6
  step(5);
  CHECK_FALSE(status.views[0].reshown);
  CHECK(app->shownSurface(0)->key.level == 5);
}

TEST_CASE("viewer app: a pivot picked at a deep pole, seen from 1e-6 of the model, lands on the surface point there") {
  auto app = makeHiddenApp(480, 360);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  settings.viewCount = 1;
  settings.showPanels = false;
  settings.views[0].scheme = SchemeChoice::RTS;
  settings.views[0].level = 20;
  app->waitUntilIdle();
  for (int frame = 0; frame < 3; ++frame) app->runFrame();  // the first frames frame the model
  glm::dvec3 pole(0.0);
  for (const Patch& patch : app->shownSurface(0)->patches)
    if (patch.kind == PatchKind::PoleCap) pole = patch.origin + patch.cp[0];
  OrbitCamera& camera = settings.camera(0);
  camera.target = pole;
  camera.distance = 1e-6;
  camera.pitchDeg = 89.0;
  app->runFrame();
  app->runFrame();
  const ViewTransform view = app->viewTransform(0);
  const auto at = view.project(pole);
  REQUIRE(at);
  // A point of the surface a few pixels beside the pole: on the surface, so its height over the
  // pole's tangent plane (normal +z at this pole) is second order in its distance (~1e-7 here).
  app->requestPivot(PivotPick{0, float(at->x) + 20.0f, float(at->y), 0.0f});
  app->runFrame();
  const glm::dvec3 picked = settings.camera(0).target;
  const double across = glm::length(glm::dvec2(picked - pole));
  CHECK(across > 1e-8);   // it moved to the picked point ...
  CHECK(across < 1e-6);   // ... which is near the pole, within the view
  // Float unprojection put it ~1e-7 off in depth (float steps near 1.6 are 1.2e-7), 40x the
  // surface's actual rise there (K ~ 0.5: ~(1e-7)^2); the depth buffer resolves ~1e-9 at this range.
  CHECK(std::abs(picked.z - pole.z) < 2e-8);
}

TEST_CASE("pole inspector: open, it lists the model's pole and computes it for each scheme shown, in the background") {
  auto app = makeHiddenApp(900, 600);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.viewCount = 3;
  settings.linkLevels = false;
  settings.views[0].scheme = SchemeChoice::C2PS;
  settings.views[1].scheme = SchemeChoice::RTS;
  settings.views[2].scheme = SchemeChoice::C2PS;  // a scheme twice is inspected once
  app->session().queueCommand("poles.inspect");     // as `view --inspect-poles`: the panel opens the section
  app->waitUntilIdle();
  for (int frame = 0; frame < 400 && (status.poleInspector.inspections.size() < 2 || status.poleInspector.computing); ++frame) {
    app->runFrame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const PoleInspectorStatus& inspector = status.poleInspector;
  REQUIRE(inspector.poles.size() == 1);
  REQUIRE(inspector.inspections.size() == 2);
  CHECK(inspector.inspections[0].scheme == SchemeChoice::C2PS);
  CHECK(inspector.inspections[1].scheme == SchemeChoice::RTS);
  // What the panel shows is what the pipeline computes.
  const PoleInspection fresh = inspectPole(*app->model().mesh, inspector.poles[0], SchemeChoice::C2PS, 10);
  REQUIRE(fresh.rings.size() == inspector.inspections[0].rings.size());
  CHECK(fresh.K == inspector.inspections[0].K);
  CHECK(fresh.rings.back().deviation == inspector.inspections[0].rings.back().deviation);
  // Another scheme shown: the open section follows it.
  settings.views[1].scheme = SchemeChoice::BPS;
  app->waitUntilIdle();
  for (int frame = 0; frame < 400 && (inspector.computing || inspector.inspections[1].scheme != SchemeChoice::BPS); ++frame) {
    app->runFrame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE(inspector.inspections.size() == 2);
  CHECK(inspector.inspections[1].scheme == SchemeChoice::BPS);
  CHECK_FALSE(inspector.inspections[1].curvatureDefined);  // BPS is C1 at the pole
}

TEST_CASE("point readout: Alt+click reads the surface point under the cursor without moving the camera") {
  auto app = makeHiddenApp(640, 480);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[0].scheme = SchemeChoice::C2PS;
  settings.views[0].level = 3;
  app->waitUntilIdle();
  for (int frame = 0; frame < 3; ++frame) app->runFrame();
  const OrbitCamera before = settings.camera(0);
  // The point projects back under the cursor, and its K is the patch's there.
  const PointReadout& r = altClickReadout(*app, 0.5f, 0.45f, [](const Point& p) { return p; });
  CHECK(settings.camera(0).target == before.target);  // Alt+click moves nothing
  CHECK(settings.camera(0).distance == before.distance);
  const SurfacePoint again = evaluatePatch(app->shownSurface(0)->patches.at(r.patchIndex), r.u, r.v);
  CHECK(again.gaussian == doctest::Approx(r.point.gaussian));
  CHECK(status.readout.text.find("K ") != std::string::npos);
}

TEST_CASE("Fig. 14 from the viewer: a cube's corners become poles that C2PS refines, Ctrl+Z brings the cube back") {
  auto app = makeHiddenApp(640, 480);
  REQUIRE(app->session().apply(app->document().loadMesh(shapes::cube(), "cube")));
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[0].scheme = SchemeChoice::C2PS;
  settings.views[0].level = 2;
  app->waitUntilIdle();
  app->runFrame();
  CHECK(status.views[0].polesByScheme == 0);
  const int cubeFaces = app->model().mesh->faceCount();
  for (bool pentagons : {false, true}) {
    CAPTURE(pentagons);
    app->session().queueCommand(pentagons ? "model.ev-to-polar-pentagons" : "model.ev-to-polar");
    app->runFrame();
    app->waitUntilIdle();
    app->runFrame();
    CHECK(app->model().mesh->faceCount() > cubeFaces);
    CHECK_FALSE(modelPoles(*app->model().mesh).empty());
    CHECK(status.views[0].polesByScheme == int(modelPoles(*app->model().mesh).size()));  // C2PS refines them
    app->session().queueCommand("file.previous-model");  // Ctrl+Z with no edit to undo
    app->runFrame();
    app->waitUntilIdle();
    CHECK(app->model().mesh->faceCount() == cubeFaces);
  }
}

TEST_CASE("Spectrum panel: RTS's Table 1 at the chosen valence, and v_k shown as the model (its net and eigenspline)") {
  auto app = makeHiddenApp(640, 480);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.spectrum.valence = 7;
  settings.spectrum.open = true;  // as the panel marks it while the section is open
  app->runFrame();
  REQUIRE(status.spectrum.linesValence == 7);
  REQUIRE(status.spectrum.lines.size() == 8);
  // Table 1: 1, 1/2, 1/2, 1/4, 1/4, 1/4.
  const double table1[] = {1.0, 0.5, 0.5, 0.25, 0.25, 0.25};
  for (int k = 0; k < 6; ++k) {
    CAPTURE(status.spectrum.lines[size_t(k)]);
    const double value = std::stod(status.spectrum.lines[size_t(k)].substr(status.spectrum.lines[size_t(k)].find(' ') + 2));
    CHECK(value == doctest::Approx(table1[k]).epsilon(1e-9));
  }
  settings.spectrum.k = 3;  // the paraboloid mode: its net's heights are the eigenvector
  app->session().queueCommand("model.eigenvector");
  app->runFrame();
  app->waitUntilIdle();
  const PolyMesh& net = *app->model().mesh;
  CHECK(net.points.size() == eigenNet(7, 3, 0).points.size());
  CHECK(modelPoles(net).size() >= 1);
  CHECK(app->model().name.find("v3") != std::string::npos);
}

TEST_CASE("pole zoom: the views draw rings m..m+2 of the pole scaled by 2^m, and the whole surface again when it is off") {
  auto app = makeHiddenApp(800, 500);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.viewCount = 2;
  settings.views[0].scheme = SchemeChoice::C2PS;
  settings.views[1].scheme = SchemeChoice::RTS;
  settings.views[0].level = settings.views[1].level = 9;
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  app->waitUntilIdle();
  app->runFrame();
  // What the renderer draws of the whole surface (its level of detail: rings below a pixel left out).
  const int whole = app->renderer(0).patchCount();
  CHECK(whole == status.views[0].drawnPatches);
  settings.poleInspector.zoomRing = 6;
  app->runFrame();
  app->runFrame();
  const BuiltSurface& shown = *app->shownSurface(0);
  const std::vector<Patch> zoomed = zoomAboutPole(shown.patches, 0, 6, 3, shown.poles[0]);
  CHECK(app->renderer(0).patchCount() == int(zoomed.size()));
  CHECK(status.views[0].zoomRing == 6);
  CHECK(viewTitle(status.views[0]).find("rings 6-8") != std::string::npos);
  const char* out = std::getenv("POLARVIEW_TEST_SHOTS");
  if (out) {
    const RgbaImage image = app->renderImage(800, 500, 1, false);
    writePngAtomic(std::string(out) + "/pole_zoom.png", image);
  }
  settings.poleInspector.zoomRing = -1;
  app->runFrame();
  CHECK(app->renderer(0).patchCount() == whole);
}

TEST_CASE("pole zoom: only the zoomed pole is marked, and Alt+click reads the surface itself at the point drawn") {
  auto app = makeHiddenApp(640, 480);
  REQUIRE(app->session().apply(app->document().loadMesh(shapes::globe(8, 6), "globe")));
  ViewerSettings& settings = app->settings();
  settings.views[0].scheme = SchemeChoice::C2PS;
  settings.views[0].level = 7;
  settings.display.poleMarkers = true;
  app->waitUntilIdle();
  settings.camera(0).pitchDeg = 60.0;
  for (int frame = 0; frame < 3; ++frame) app->runFrame();
  const BuiltSurface& shown = *app->shownSurface(0);
  REQUIRE(shown.poles.size() == 2);
  // The pole in sight from above is marked.
  const ViewTransform before = app->viewTransform(0);
  REQUIRE(app->lastPoleMarkers().size() == 1);
  int top = -1;
  for (int p = 0; p < 2; ++p) {
    const auto at = before.project(shown.poles[size_t(p)]);
    if (at && std::hypot(at->x - app->lastPoleMarkers()[0].x, at->y - app->lastPoleMarkers()[0].y) < 2.0) top = p;
  }
  REQUIRE(top >= 0);
  // Zoomed on the other pole (its rings scaled by 16 about it, nothing else drawn), the top pole,
  // still inside the view, is not marked: at most the zoomed pole is, where it is.
  const int zoomed = 1 - top;
  settings.poleInspector.pole = zoomed;
  settings.poleInspector.zoomRing = 4;
  for (int frame = 0; frame < 3; ++frame) app->runFrame();
  const ViewTransform view = app->viewTransform(0);
  const auto topAt = view.project(shown.poles[size_t(top)]);
  REQUIRE(topAt);
  CHECK(view.rect.contains(float(topAt->x), float(topAt->y)));
  CHECK(app->lastPoleMarkers().size() <= 1);
  for (const PoleMarker& marker : app->lastPoleMarkers()) {
    const auto at = view.project(shown.poles[size_t(zoomed)]);
    REQUIRE(at);
    CHECK(std::hypot(at->x - marker.x, at->y - marker.y) < 2.0);
  }
  // Framed (F) on the zoomed rings, Alt+click reads the surface itself, scaled back about the pole.
  app->frameModel();
  for (int frame = 0; frame < 3; ++frame) app->runFrame();
  const Point& pole = shown.poles[size_t(zoomed)];
  const PointReadout& r = altClickReadout(*app, 0.6f, 0.5f, [&](const Point& p) { return pole + 16.0 * (p - pole); });
  CHECK(shown.patches.at(r.patchIndex).pole == zoomed);
  const SurfacePoint again = evaluatePatch(shown.patches.at(r.patchIndex), r.u, r.v);
  CHECK(glm::length(again.position - r.point.position) < 1e-9);
}

}  // namespace polarview
