// A whole viewer session without a window: commands load models, the surfaces follow, a failed
// load keeps the model, Ctrl+Z returns to the previous model, and saves and exports write files.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "core/mesh/constants.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "session/session.h"

using namespace polarview;

namespace {

// The window's part, recorded.
struct FakeWindow : WindowServices {
  int framed = 0, screenshots = 0;
  std::string clipboardText;
  void frameModel() override { ++framed; }
  void setClipboard(const std::string& text) override { clipboardText = text; }
  std::string clipboard() override { return clipboardText; }
  void takeScreenshot() override { ++screenshots; }
};

// The frame loop's session part, until nothing is left to do.
void settle(Session& session) {
  do {
    session.runCommands();
    session.updateModelAndSurfaces();
    session.updatePanels();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  } while (session.busy() || !session.state().queuedCommands.empty());
}

std::filesystem::path freshDirectory() {
  std::random_device random;
  const auto path = std::filesystem::temp_directory_path() / ("polarview_session_" + std::to_string(random()));
  std::filesystem::create_directories(path);
  return path;
}

SessionOptions quiet() {
  SessionOptions options;
  options.persistRecent = false;  // tests leave ~/.config alone
  options.prepareNextLevel = false;
  return options;
}

}  // namespace

TEST_CASE("session: the default model through a command, its surface, and a failed load that keeps it") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  queueCommand(state, "file.default");
  settle(session);
  REQUIRE(session.model().mesh != nullptr);
  CHECK(window.framed == 1);
  CHECK(state.file.modelName.rfind("default", 0) == 0);
  REQUIRE(session.surfaces().shown(0) != nullptr);
  CHECK(session.surfaces().shown(0)->key == wantedKey(state, session.model(), 0));
  CHECK(state.views[0].status.patchCount > 0);

  const uint64_t generation = session.model().generation;
  state.file.pathField = "/nonexistent/model.obj";
  queueCommand(state, "file.open");
  settle(session);
  CHECK(session.model().generation == generation);  // the model stays
  CHECK_FALSE(state.file.error.empty());
  CHECK(state.notice.find("could not open /nonexistent/model.obj") == 0);
}

TEST_CASE("session: Ctrl+Z with no edit returns to the model replaced last, again to redo") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  REQUIRE(session.document().loadMesh(shapes::cube(), "cube"));
  REQUIRE(session.document().loadMesh(shapes::mushroom(6), "mushroom"));
  settle(session);
  queueCommand(state, "edit.undo");
  settle(session);
  CHECK(session.model().name == "cube");
  CHECK(session.surfaces().shown(0)->key.model == session.model().generation);
  queueCommand(state, "edit.undo");
  settle(session);
  CHECK(session.model().name == "mushroom");
}

TEST_CASE("session: a cylinder's n-gon caps have no pole; N-gons to triangle fans makes two, Ctrl+Z returns") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  const std::filesystem::path dir = freshDirectory();
  const std::string path = (dir / "cylinder.obj").string();
  saveObj(path, shapes::ngonCylinder(24));
  state.file.pathField = path;
  queueCommand(state, "file.open");
  settle(session);
  REQUIRE(state.file.loadedPath == path);
  const PoleInspectorSettings& inspector = state.poleInspector;
  CHECK(inspector.poles.empty());
  CHECK(inspector.survey.fanFaces == 2);  // what the Poles panel offers to convert
  CHECK(inspector.survey.rejectedCount == 0);

  queueCommand(state, "model.ngon-to-fan");
  settle(session);
  CHECK(state.file.modelFaces == 24 + 2 * 24);
  REQUIRE(inspector.poles.size() == 2);
  CHECK(inspector.poles == std::vector<Index>{48, 49});
  CHECK(inspector.survey.fanFaces == 0);
  CHECK(state.notice.find("2 faces made triangle fans") == 0);
  CHECK(session.surfaces().shown(0)->key.model == session.model().generation);
  CHECK(state.views[0].status.polesByScheme == 2);  // C2PS refines both

  queueCommand(state, "edit.undo");
  settle(session);
  CHECK(state.file.modelFaces == 26);
  CHECK(inspector.poles.empty());
  CHECK(inspector.survey.fanFaces == 2);
  // Nothing to convert: a notice, the model stays.
  const uint64_t generation = session.model().generation;
  REQUIRE(session.document().loadMesh(shapes::globe(8, 3), "globe"));
  settle(session);
  queueCommand(state, "model.ngon-to-fan");
  settle(session);
  CHECK(session.model().generation == generation + 1);
  CHECK(state.notice.find("no face with 5 or more sides") == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("session: the Poles panel's candidates that are not poles, the nearest first, with reasons") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  // A cone without a base (its 16-valent fan's rim is a boundary) and, apart, an octahedron (six
  // 4-valent fans ringed by triangles, no quads).
  PolyMesh cone;
  for (int i = 0; i < 16; ++i) cone.points.push_back({std::cos(i * kPi / 8), std::sin(i * kPi / 8), 0.0});
  cone.points.push_back({0.0, 0.0, 2.0});
  for (int i = 0; i < 16; ++i) cone.addFace({i, (i + 1) % 16, 16});
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      Point p(5.0, 0.0, 0.0);
      p[axis] += sign;
      cone.points.push_back(p);  // 17 + 2 axis + (sign < 0)
    }
  for (int octant = 0; octant < 8; ++octant) {
    const Index x = 17 + (octant & 1), y = 19 + (octant >> 1 & 1), z = 21 + (octant >> 2 & 1);
    const bool outward = (__builtin_popcount(unsigned(octant)) % 2) == 0;  // an even number of minus signs
    if (outward) cone.addFace({x, y, z});
    else cone.addFace({x, z, y});
  }
  REQUIRE(session.document().loadMesh(cone, "cone"));
  settle(session);
  const PoleSurvey& survey = state.poleInspector.survey;
  CHECK(state.poleInspector.poles.empty());
  REQUIRE(survey.rejected.size() == 2);
  CHECK(survey.rejectedCount == 1 + 6);
  CHECK(survey.rejected[0].words == "a 1-link vertex is on a boundary");
  REQUIRE(survey.rejected[0].nearest.size() == 1);
  CHECK(survey.rejected[0].nearest[0].vertex == 16);
  CHECK(survey.rejected[0].nearest[0].valence == 16);
  CHECK(survey.rejected[0].nearest[0].reason.find("is on a boundary") != std::string::npos);
  // The octahedron's six, the first three by vertex id listed.
  CHECK(survey.rejected[1].words == "a 1-link vertex is not between 2 triangles and 2 quads");
  CHECK(survey.rejected[1].count == 6);
  REQUIRE(survey.rejected[1].nearest.size() == 3);
  CHECK(survey.rejected[1].nearest[0].vertex == 17);
  CHECK(survey.rejected[1].nearest[2].valence == 4);
  CHECK(survey.fanFaces == 0);
}

TEST_CASE("session: Save OBJ and Export .bv write what the model and the active view are") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  REQUIRE(session.document().loadMesh(shapes::mushroom(6), "mushroom"));
  state.views[0].level = 2;
  settle(session);
  const std::filesystem::path folder = freshDirectory();
  state.edit.savePath = (folder / "saved.obj").string();
  state.edit.bvPath = (folder / "surface.bv").string();
  queueCommand(state, "edit.save");
  queueCommand(state, "export.bv");
  settle(session);
  CHECK(state.edit.error.empty());
  const PolyMesh saved = loadObj(state.edit.savePath);
  CHECK(saved.faceCount() == session.model().mesh->faceCount());
  CHECK(saved.points == session.model().mesh->points);
  // BezierView's file: one record a patch, as many as the view's patches.
  std::ifstream bv(state.edit.bvPath);
  REQUIRE(bv.good());
  CHECK(state.notice.find(std::to_string(session.surfaces().shown(0)->patches.size()) + " Bezier patches") != std::string::npos);
  std::filesystem::remove_all(folder);
}

TEST_CASE("session: after an eigenvector net and Ctrl+Z, the outputs are named after the default model again") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  queueCommand(state, "file.default");
  settle(session);
  CHECK(state.edit.defaultSavePath == "default_edited.obj");
  queueCommand(state, "model.eigenvector");
  settle(session);
  CHECK(state.file.modelName.rfind("RTS eigenvector", 0) == 0);
  queueCommand(state, "edit.undo");  // no vertex drag to undo: back to the default model
  settle(session);
  CHECK(state.file.modelName.rfind("default: ", 0) == 0);
  CHECK(state.edit.defaultSavePath == "default_edited.obj");
  CHECK(state.edit.defaultBvPath.rfind("default_c2ps_", 0) == 0);
}
