// Live editing of the base control mesh, driven through the real input path (the pointer ImGui
// reads, ViewerApp::overridePointer): a click near a control vertex picks it, a drag moves it in
// the view plane under the cursor while every view follows from a positions-only update of its
// kept refinement, undo / redo / reset work over whole drags, Ctrl+S saves the edited mesh, and
// the Export entries write the shown surface (.bv) and the uniform refined control mesh (OBJ).
#include <GLFW/glfw3.h>

#include "app_test_support.h"
#include "pipeline/patch_export.h"
#include "pipeline/surface_export.h"
#include "pipeline/surface_measures.h"
#include "app/viewer_app.h"
#include "session/settings_rules.h"
#include "pipeline/vertex_edit.h"
#include "render/patch_renderer.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"
#include "core/mesh/obj_io.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/refiner.h"

#include <doctest/doctest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

namespace polarview {
namespace {

namespace fs = std::filesystem;


// The default model at `level`, control net shown, panels hidden (the views fill the window).
std::unique_ptr<ViewerApp> makeEditingApp(int level, int views = 1) {
  auto app = makeHiddenApp(800, 600);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  settings.showPanels = false;
  settings.display.controlNet = true;
  settings.viewCount = views;
  requestLevel(settings, app->status(), app->notices(), level);
  app->waitUntilIdle();
  app->runFrame();
  app->waitUntilIdle();
  return app;
}

// The pointer ImGui sees, one frame per call.
void pointer(ViewerApp& app, float x, float y, bool left) {
  app.overridePointer(PointerState{x, y, left});
  app.runFrame();
}

// A drag with the left button from (x0, y0) to (x1, y1) in `steps` frames, then the release.
void drag(ViewerApp& app, float x0, float y0, float x1, float y1, int steps = 4) {
  pointer(app, x0, y0, false);
  pointer(app, x0, y0, true);
  for (int i = 1; i <= steps; ++i) {
    const float t = float(i) / float(steps);
    pointer(app, x0 + t * (x1 - x0), y0 + t * (y1 - y0), true);
  }
  pointer(app, x1, y1, false);
}

// The control vertex whose projection is nearest the middle of view 0, and where it appears.
struct ScreenVertex {
  int vertex = -1;
  float x = 0, y = 0;
};
ScreenVertex centralVertex(const ViewerApp& app, int view = 0) {
  const ViewTransform transform = app.viewTransform(view);
  const float cx = transform.rect.x + 0.5f * transform.rect.w, cy = transform.rect.y + 0.5f * transform.rect.h;
  ScreenVertex best;
  double bestDistance = std::numeric_limits<double>::infinity();
  const std::vector<Point>& points = app.document().editor().points();
  for (size_t i = 0; i < points.size(); ++i) {
    const auto at = transform.project(points[i]);
    if (!at) continue;
    const double d = std::hypot(at->x - cx, at->y - cy);
    if (d < bestDistance) {
      bestDistance = d;
      best = {int(i), float(at->x), float(at->y)};
    }
  }
  return best;
}

// Every patch of `a` equals the one at the same place in `b` to `tolerance` (positions and cap data).
void checkSamePatches(const std::vector<Patch>& a, const std::vector<Patch>& b, double tolerance) {
  REQUIRE(a.size() == b.size());
  double worst = 0.0;
  size_t kindsDiffer = 0;
  for (size_t p = 0; p < a.size(); ++p) {
    kindsDiffer += a[p].kind != b[p].kind;
    for (int k = 0; k < 16; ++k)
      worst = std::max(worst, glm::length(withAbsolutePositions(a[p]).cp[k] - withAbsolutePositions(b[p]).cp[k]));
  }
  CHECK(kindsDiffer == 0);
  CHECK(worst <= tolerance);
}

bool noTemporariesIn(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".tmp") return false;
  return true;
}

}  // namespace

TEST_CASE("vertex editing: a click near a control vertex selects it, a drag on empty space still orbits") {
  auto app = makeEditingApp(2);
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  const ScreenVertex target = centralVertex(*app);
  REQUIRE(target.vertex >= 0);
  // The expected pick: among the vertices within 8 px of the click, the one nearest the eye.
  const float clickX = target.x + 3.0f, clickY = target.y - 2.0f;
  const ViewTransform transform = app->viewTransform(0);
  int expected = -1;
  double nearest = 2.0;
  for (size_t i = 0; i < app->document().editor().points().size(); ++i) {
    const auto at = transform.project(app->document().editor().points()[i]);
    if (at && std::hypot(at->x - clickX, at->y - clickY) <= 8.0 && at->z < nearest) {
      nearest = at->z;
      expected = int(i);
    }
  }
  REQUIRE(expected >= 0);
  const OrbitCamera before = settings.sharedCamera;
  pointer(*app, clickX, clickY, false);
  pointer(*app, clickX, clickY, true);
  CHECK(app->document().editor().selected() == expected);
  CHECK(status.edit.selectedVertex == expected);
  pointer(*app, clickX, clickY, false);
  CHECK(app->document().editor().selected() == expected);
  CHECK(app->document().editor().undoCount() == 0);  // a click without motion moves nothing
  CHECK(cameraToJson(settings.sharedCamera) == cameraToJson(before));

  // A drag from a spot far from every vertex orbits, and keeps the selection.
  const float emptyX = transform.rect.x + 12.0f, emptyY = transform.rect.y + transform.rect.h - 12.0f;
  REQUIRE(pickVertex(app->document().editor().points(), transform, emptyX, emptyY) == -1);
  drag(*app, emptyX, emptyY, emptyX + 60.0f, emptyY - 20.0f);
  CHECK(settings.sharedCamera.yawDeg != doctest::Approx(before.yawDeg));
  CHECK(app->document().editor().selected() == expected);
  CHECK(app->document().editor().points() == app->document().editor().loadedPoints());
  // A click (no drag) there clears the selection; with the net hidden a press never picks.
  const ViewTransform turned = app->viewTransform(0);
  REQUIRE(pickVertex(app->document().editor().points(), turned, emptyX + 40.0f, emptyY - 40.0f) == -1);
  pointer(*app, emptyX + 40.0f, emptyY - 40.0f, false);
  pointer(*app, emptyX + 40.0f, emptyY - 40.0f, true);
  pointer(*app, emptyX + 40.0f, emptyY - 40.0f, false);
  CHECK(app->document().editor().selected() == -1);
  settings.display.controlNet = false;
  const ScreenVertex again = centralVertex(*app);
  pointer(*app, again.x, again.y, false);
  pointer(*app, again.x, again.y, true);
  pointer(*app, again.x, again.y, false);
  CHECK(app->document().editor().selected() == -1);
}

TEST_CASE("vertex editing: a drag moves the vertex in the view plane under the cursor, the topology is never rebuilt") {
  auto app = makeEditingApp(3, 2);
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[1].scheme = SchemeChoice::CatmullClark;
  app->waitUntilIdle();
  app->runFrame();
  const ScreenVertex target = centralVertex(*app);
  REQUIRE(target.vertex >= 0);
  const Point start = app->model().mesh->points[size_t(target.vertex)];
  const std::vector<Index> faces = app->model().mesh->faceVerts;
  const std::vector<Point> loaded = app->model().mesh->points;
  const glm::dvec3 forward = settings.sharedCamera.forward();
  const AdaptiveRefinement* refinements[2] = {app->shownSurface(0)->refinement.get(), app->shownSurface(1)->refinement.get()};
  const int patches[2] = {status.views[0].patchCount, status.views[1].patchCount};
  const uint64_t generation = app->modelGeneration();

  // Press on the vertex, then move frame by frame: every frame each view shows the new points.
  pointer(*app, target.x, target.y, false);
  pointer(*app, target.x, target.y, true);
  REQUIRE(app->document().editor().dragging());
  for (int step = 1; step <= 5; ++step) {
    const float x = target.x + 6.0f * float(step), y = target.y + 4.0f * float(step);
    pointer(*app, x, y, true);
    CAPTURE(step);
    const Point moved = app->model().mesh->points[size_t(target.vertex)];
    const auto at = app->viewTransform(0).project(moved);
    REQUIRE(at);
    CHECK(at->x == doctest::Approx(x).epsilon(1e-6));
    CHECK(at->y == doctest::Approx(y).epsilon(1e-6));
    CHECK(std::abs(glm::dot(moved - start, forward)) < 1e-9 * glm::length(moved - start) + 1e-15);
    for (int v = 0; v < 2; ++v) {
      CAPTURE(v);
      const BuiltSurface* shown = app->shownSurface(v);
      CHECK(shown->key.points == app->model().points);
      CHECK(shown->refinement.get() == refinements[v]);  // same hierarchy: topology not rebuilt
      CHECK(int(shown->patches.size()) == patches[v]);
      CHECK(shown->controlMesh.points[size_t(target.vertex)] == moved);
      CHECK(status.views[size_t(v)].patchCount == patches[v]);
    }
  }
  pointer(*app, target.x + 30.0f, target.y + 20.0f, false);
  CHECK_FALSE(app->document().editor().dragging());
  CHECK(app->document().editor().undoCount() == 1);
  // Only that vertex moved; faces, model generation and face counts are as loaded.
  for (size_t i = 0; i < loaded.size(); ++i)
    if (int(i) != target.vertex) CHECK(app->model().mesh->points[i] == loaded[i]);
  CHECK(app->model().mesh->faceVerts == faces);
  CHECK(app->modelGeneration() == generation);
  CHECK(app->document().editCosts().size() >= 5);
  CHECK(status.edit.updatedViews == 2);
  // After the release the curvature samples are retaken for the new points.
  app->waitUntilIdle();
  CHECK(app->shownSurface(0)->samples->points == app->model().points);
}

TEST_CASE("vertex editing: a press and a quick move within one frame still grab the vertex where it was pressed") {
  auto app = makeEditingApp(2);
  const ScreenVertex target = centralVertex(*app);
  REQUIRE(target.vertex >= 0);
  // The window's callbacks, as GLFW calls them: the cursor at the vertex, the press there, and by
  // the time the frame reads the mouse the cursor is already 30 px away.
  GLFWcursorposfun cursor = glfwSetCursorPosCallback(app->window(), nullptr);
  glfwSetCursorPosCallback(app->window(), cursor);
  GLFWmousebuttonfun button = glfwSetMouseButtonCallback(app->window(), nullptr);
  glfwSetMouseButtonCallback(app->window(), button);
  REQUIRE(bool(cursor));
  REQUIRE(bool(button));
  const float x1 = target.x + 24.0f, y1 = target.y + 18.0f;
  pointer(*app, target.x, target.y, false);
  cursor(app->window(), target.x, target.y);
  button(app->window(), GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0);
  cursor(app->window(), x1, y1);
  pointer(*app, x1, y1, true);
  CHECK(app->document().editor().dragging());
  CHECK(app->document().editor().selected() == target.vertex);
  pointer(*app, x1, y1, true);
  const auto at = app->viewTransform(0).project(app->model().mesh->points[size_t(target.vertex)]);
  REQUIRE(at);
  CHECK(at->x == doctest::Approx(x1).epsilon(1e-6));
  CHECK(at->y == doctest::Approx(y1).epsilon(1e-6));
  button(app->window(), GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0);
  pointer(*app, x1, y1, false);
  CHECK_FALSE(app->document().editor().dragging());
  CHECK(app->document().editor().undoCount() == 1);
}

TEST_CASE("vertex editing: after a drag every view's patches equal a fresh build of the edited mesh") {
  auto app = makeEditingApp(3, 3);
  ViewerSettings& settings = app->settings();
  settings.views[1].scheme = SchemeChoice::CatmullClark;
  settings.views[2].scheme = SchemeChoice::BPS;
  app->waitUntilIdle();
  app->runFrame();
  const ScreenVertex target = centralVertex(*app);
  REQUIRE(target.vertex >= 0);
  drag(*app, target.x, target.y, target.x - 25.0f, target.y + 18.0f);
  // And a second vertex, picked in another view.
  const ScreenVertex other = centralVertex(*app, 1);
  REQUIRE(other.vertex >= 0);
  drag(*app, other.x, other.y, other.x + 10.0f, other.y - 30.0f);
  app->waitUntilIdle();
  REQUIRE(app->document().editor().undoCount() == 2);
  const double scale = glm::length(app->document().modelMax() - app->document().modelMin());
  for (int v = 0; v < 3; ++v) {
    CAPTURE(v);
    const BuiltSurface* shown = app->shownSurface(v);
    auto fresh = buildSurface(app->model(), shown->key, kDefaultFaceBudget);
    checkSamePatches(shown->patches, fresh->patches, 1e-12 * scale);
    REQUIRE(shown->poles.size() == fresh->poles.size());
    for (size_t p = 0; p < shown->poles.size(); ++p) CHECK(glm::length(shown->poles[p] - fresh->poles[p]) <= 1e-12 * scale);
    CHECK(shown->samples->gaussian.size() == fresh->samples->gaussian.size());
  }
}

TEST_CASE("vertex editing: undo restores the loaded points exactly, redo reapplies, Reset returns to the file") {
  auto app = makeEditingApp(2);
  ViewerStatus& status = app->status();
  const std::vector<Point> loaded = app->model().mesh->points;
  const std::vector<Patch> loadedPatches = app->shownSurface(0)->patches;
  GLFWkeyfun key = glfwSetKeyCallback(app->window(), nullptr);
  glfwSetKeyCallback(app->window(), key);
  REQUIRE(bool(key));
  auto press = [&](int k, int mods) {
    key(app->window(), k, 0, GLFW_PRESS, mods);
    key(app->window(), k, 0, GLFW_RELEASE, mods);
    app->runFrame();
  };

  const ScreenVertex first = centralVertex(*app);
  drag(*app, first.x, first.y, first.x + 20.0f, first.y);
  const std::vector<Point> afterFirst = app->model().mesh->points;
  drag(*app, first.x + 20.0f, first.y, first.x + 20.0f, first.y - 25.0f);  // the same vertex again
  const std::vector<Point> afterSecond = app->model().mesh->points;
  REQUIRE(afterFirst != loaded);
  REQUIRE(afterSecond != afterFirst);
  CHECK(app->document().editor().undoCount() == 2);

  press(GLFW_KEY_Z, GLFW_MOD_CONTROL);
  CHECK(app->model().mesh->points == afterFirst);
  press(GLFW_KEY_Z, GLFW_MOD_CONTROL);
  CHECK(app->model().mesh->points == loaded);
  CHECK(status.edit.movedVertices == 0);
  app->waitUntilIdle();
  checkSamePatches(app->shownSurface(0)->patches, loadedPatches, 1e-13 * glm::length(app->document().modelMax() - app->document().modelMin()));
  press(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT);
  CHECK(app->model().mesh->points == afterFirst);
  press(GLFW_KEY_Y, GLFW_MOD_CONTROL);
  CHECK(app->model().mesh->points == afterSecond);
  CHECK(app->document().editor().redoCount() == 0);
  CHECK(status.edit.movedVertices == 1);

  // Reset (the panel's button): back to the file's points, itself undoable.
  app->session().queueCommand("edit.reset");
  app->runFrame();
  CHECK(app->model().mesh->points == loaded);
  press(GLFW_KEY_Z, GLFW_MOD_CONTROL);
  CHECK(app->model().mesh->points == afterSecond);
  // A new drag after an undo drops the redo steps.
  press(GLFW_KEY_Z, GLFW_MOD_CONTROL);
  REQUIRE(app->document().editor().redoCount() > 0);
  const ScreenVertex again = centralVertex(*app);
  drag(*app, again.x, again.y, again.x - 15.0f, again.y);
  CHECK(app->document().editor().redoCount() == 0);
}

TEST_CASE("vertex editing: Ctrl+S saves the edited mesh as OBJ that loads back to the edited points, a failed save leaves nothing") {
  auto app = makeEditingApp(2);
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  CHECK(status.edit.defaultSavePath == "default_edited.obj");  // the built-in model: the current directory
  const ScreenVertex target = centralVertex(*app);
  drag(*app, target.x, target.y, target.x + 17.0f, target.y + 9.0f);
  REQUIRE(app->document().editor().undoCount() == 1);

  const fs::path dir = fs::temp_directory_path() / "polarview_edit_save";
  fs::remove_all(dir);
  fs::create_directories(dir);
  settings.edit.savePath = (dir / "edited.obj").string();
  GLFWkeyfun key = glfwSetKeyCallback(app->window(), nullptr);
  glfwSetKeyCallback(app->window(), key);
  key(app->window(), GLFW_KEY_S, 0, GLFW_PRESS, GLFW_MOD_CONTROL);
  key(app->window(), GLFW_KEY_S, 0, GLFW_RELEASE, GLFW_MOD_CONTROL);
  app->runFrame();
  CAPTURE(app->notices().text());
  CHECK(status.edit.error.empty());
  PolyMesh saved = loadObj((dir / "edited.obj").string());
  CHECK(saved.points == app->model().mesh->points);  // 17 significant digits: exact
  CHECK(saved.faceVerts == app->model().mesh->faceVerts);
  CHECK(saved.faceStart == app->model().mesh->faceStart);

  // A folder that does not exist: one line of error, no file, no temporary.
  settings.edit.savePath = (dir / "missing" / "edited.obj").string();
  app->session().queueCommand("edit.save");
  app->runFrame();
  CHECK_FALSE(status.edit.error.empty());
  CHECK(status.edit.error.find('\n') == std::string::npos);
  CHECK_FALSE(fs::exists(dir / "missing" / "edited.obj"));
  CHECK(noTemporariesIn(dir));

  // A model opened from a file saves beside it.
  saveObj((dir / "cage.obj").string(), *app->model().mesh);
  REQUIRE(app->session().apply(app->document().loadFile((dir / "cage.obj").string())));
  app->runFrame();
  CHECK(status.edit.defaultSavePath == (dir / "cage_edited.obj").string());
  CHECK(app->document().editor().undoCount() == 0);  // a new model starts a new history
  fs::remove_all(dir);
}

TEST_CASE("export from the viewer: .bv of the shown surface as the export command writes it, the refined control mesh as OBJ") {
  auto app = makeEditingApp(2);
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  const ScreenVertex target = centralVertex(*app);
  drag(*app, target.x, target.y, target.x + 12.0f, target.y - 12.0f);
  app->waitUntilIdle();
  const fs::path dir = fs::temp_directory_path() / "polarview_edit_export";
  fs::remove_all(dir);
  fs::create_directories(dir);

  // .bv: the same bytes as exportPatchSet + writeSurfaceFile (`export`) of the edited mesh.
  CHECK(status.edit.defaultSurfacePath == "default_c2ps_2.bv");
  settings.edit.surfacePath = (dir / "view.bv").string();
  app->session().queueCommand("export.surface");
  app->runFrame();
  app->waitUntilIdle();
  CAPTURE(app->notices().text());
  CHECK(status.edit.error.empty());
  const RefineOptions options = refineOptionsFor(SchemeChoice::C2PS, 2);
  const PatchSet set = exportPatchSet(*app->model().mesh, options, app->model().name, false, 2 * kDefaultFaceBudget);
  ExportSettings written;
  written.source = app->model().name;
  writeSurfaceFile((dir / "cli.bv").string(), set, *exportFormatNamed("bv"), written);  // as `export` writes it
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  CHECK(bytes(dir / "view.bv").size() > 1000);
  CHECK(bytes(dir / "view.bv") == bytes(dir / "cli.bv"));
  CHECK(app->notices().text().find("wrote ") == 0);

  // Refined control mesh: the uniform refinement's finest mesh of the edited points.
  settings.edit.refinedObjPath = (dir / "refined.obj").string();
  app->session().queueCommand("export.refined-obj");
  app->runFrame();
  app->waitUntilIdle();
  CHECK(status.edit.error.empty());
  const Refinement refinement(*app->model().mesh, options);
  const PolyMesh refined = loadObj((dir / "refined.obj").string());
  CHECK(refined.faceVerts == refinement.finest().mesh.faceVerts);
  CHECK(refined.points == refinement.finest().mesh.points);

  // An unwritable path: one line of error and no file.
  settings.edit.surfacePath = (dir / "missing" / "view.bv").string();
  app->session().queueCommand("export.surface");
  app->runFrame();
  app->waitUntilIdle();
  CHECK_FALSE(status.edit.error.empty());
  CHECK(status.edit.error.find('\n') == std::string::npos);
  CHECK_FALSE(fs::exists(dir / "missing"));
  CHECK(noTemporariesIn(dir));
  fs::remove_all(dir);
}

TEST_CASE("measure from the viewer: the shown surface's area and volume are `measure`'s of the same patches") {
  auto app = makeEditingApp(2);
  app->session().queueCommand("surface.measure");
  const MeasureStatus& measures = app->status().measures;
  for (int frame = 0; frame < 2000 && (frame == 0 || measures.computing); ++frame) {
    app->runFrame();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  CAPTURE(measures.text);
  const PatchSet set = exportPatchSet(*app->model().mesh, refineOptionsFor(SchemeChoice::C2PS, 2), app->model().name,
                                      false, 2 * kDefaultFaceBudget);
  const SurfaceMeasures expected = measureSurface(set.patches, true);
  char area[64], volume[64];
  std::snprintf(area, sizeof area, "area %.10g ", expected.area);
  std::snprintf(volume, sizeof volume, "volume %.10g ", expected.volume);
  CHECK(measures.text.rfind("C2PS level 2: ", 0) == 0);
  CHECK(measures.text.find(area) != std::string::npos);
  CHECK(measures.text.find(volume) != std::string::npos);
  char centroid[96];
  std::snprintf(centroid, sizeof centroid, "centroid (%.6g, %.6g, %.6g)", expected.centroid.x, expected.centroid.y,
                expected.centroid.z);
  CHECK(measures.text.find(centroid) != std::string::npos);
  CHECK(expected.volume > 4.0);  // the mushroom: about 4.77 at level 3
}

TEST_CASE("export from the viewer: a refined control mesh over the budget is refused with a message and writes nothing") {
  const size_t budget = 20000;  // adaptive faces; the uniform budget is 20000 * 450 / 300
  auto app = makeHiddenApp(640, 400, budget);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.showPanels = false;
  const int deepest = deepestLevel(app->model(), SchemeChoice::C2PS, budget);
  requestLevel(settings, status, app->notices(), deepest);
  app->waitUntilIdle();
  app->runFrame();
  REQUIRE(app->shownSurface(0)->key.level == deepest);
  const size_t uniformBudget = budget * kBytesPerAdaptiveFace / kBytesPerUniformFace;
  REQUIRE(estimateFaceCount(*app->model().mesh, refineOptionsFor(SchemeChoice::C2PS, deepest)) > uniformBudget);
  const fs::path out = fs::temp_directory_path() / "polarview_refused_refined.obj";
  fs::remove(out);
  settings.edit.refinedObjPath = out.string();
  app->session().queueCommand("export.refined-obj");
  app->runFrame();
  app->waitUntilIdle();
  CAPTURE(status.edit.error);
  CHECK(status.edit.error.find("refined control mesh refused: C2PS level " + std::to_string(deepest)) == 0);
  CHECK(status.edit.error.find("over the budget of " + std::to_string(uniformBudget)) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("scheme toggles: back to the scheme shown before is a swap (the same surface and image), not after an edit") {
  auto app = makeEditingApp(4);
  ViewerSettings& settings = app->settings();
  ViewerStatus& status = app->status();
  settings.views[0].scheme = SchemeChoice::C2PS;
  app->waitUntilIdle();
  app->runFrame();
  const BuiltSurface* c2ps = app->shownSurface(0);
  const RgbaImage before = app->renderImage(400, 300, 1, false);

  auto toggle = [&](SchemeChoice scheme) {
    settings.views[0].scheme = scheme;
    app->runFrame();
    app->waitUntilIdle();
    app->runFrame();
    REQUIRE(app->shownSurface(0)->key.scheme == scheme);
  };
  toggle(SchemeChoice::CatmullClark);
  const BuiltSurface* catmullClark = app->shownSurface(0);
  CHECK(catmullClark != c2ps);
  CHECK_FALSE(status.views[0].unparked);
  CHECK(app->renderer(0).patchCount() == int(catmullClark->patches.size()));

  toggle(SchemeChoice::C2PS);
  CHECK(app->shownSurface(0) == c2ps);  // not rebuilt
  CHECK(status.views[0].unparked);
  CHECK(app->renderer(0).patchCount() == int(c2ps->patches.size()));
  const RgbaImage again = app->renderImage(400, 300, 1, false);
  CHECK(again.pixels == before.pixels);

  toggle(SchemeChoice::CatmullClark);  // and forth: the Catmull-Clark surface was parked in turn
  CHECK(app->shownSurface(0) == catmullClark);
  CHECK(status.views[0].unparked);

  // Moved points: the parked C2PS surface is stale, toggling back builds the edited one.
  const ScreenVertex target = centralVertex(*app);
  REQUIRE(target.vertex >= 0);
  drag(*app, target.x, target.y, target.x + 20.0f, target.y - 15.0f);
  app->waitUntilIdle();
  REQUIRE(app->document().editor().undoCount() == 1);
  toggle(SchemeChoice::C2PS);
  const BuiltSurface* edited = app->shownSurface(0);
  CHECK_FALSE(status.views[0].unparked);
  CHECK(edited->key.points == app->model().points);
  const double scale = glm::length(app->document().modelMax() - app->document().modelMin());
  checkSamePatches(edited->patches, buildSurface(app->model(), edited->key, kDefaultFaceBudget)->patches, 1e-12 * scale);
}

TEST_CASE("scheme toggles: a parked surface counts every level its refinement holds against the budget") {
  // A budget for one C2PS level 8 and a half: a parked C2PS surface shown at level 4 still holds
  // level 8 (stepped down from it), so C2PS-U 8 beside it would not fit: the parked one goes.
  std::unique_ptr<ViewerApp> probe = makeHiddenApp(400, 300);
  probe->session().apply(probe->document().loadDefaultModel());
  const size_t level8 = estimatedLevelFaces(probe->model(), SchemeChoice::C2PS, 8);
  probe.reset();
  auto app = makeHiddenApp(400, 300, level8 + level8 / 2);
  app->session().apply(app->document().loadDefaultModel());
  ViewerSettings& settings = app->settings();
  auto show = [&](SchemeChoice scheme, int level) {
    settings.views[0].scheme = scheme;
    settings.views[0].level = level;
    app->runFrame();
    app->waitUntilIdle();
    app->runFrame();
    REQUIRE(app->shownSurface(0)->key.scheme == scheme);
    REQUIRE(app->shownSurface(0)->key.level == level);
  };
  show(SchemeChoice::C2PS, 8);
  show(SchemeChoice::C2PS, 4);  // the same refinement, stepped down: it keeps level 8
  REQUIRE(app->shownSurface(0)->hierarchy->deepestMade.load() >= 8);
  show(SchemeChoice::C2PSUniformFirstStep, 4);
  REQUIRE(app->parkedSurface(0) != nullptr);  // C2PS parked (8 + 4 + 4 levels' faces fit)
  show(SchemeChoice::C2PSUniformFirstStep, 8);
  CHECK(app->parkedSurface(0) == nullptr);  // it went for C2PS-U 8's refinement
}

}  // namespace polarview
