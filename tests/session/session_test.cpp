// A whole viewer session without a window: commands load models, the surfaces follow, a failed
// load keeps the model, Ctrl+Z returns to the previous model, and saves and exports write files.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <glm/geometric.hpp>

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

TEST_CASE("session: a sphere's K (all > 0) gets a one-sided automatic range over its own values, not +-max") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  REQUIRE(session.document().loadMesh(shapes::globe(16, 7), "globe"));
  state.views[0].level = 3;
  state.shading.mode = ShadingParams::Mode::Gaussian;
  settle(session);
  REQUIRE(session.surfaces().shown(0) != nullptr);
  const std::vector<double>& k = session.surfaces().shown(0)->samples->gaussian;
  const double lowest = *std::min_element(k.begin(), k.end()), highest = *std::max_element(k.begin(), k.end());
  REQUIRE(lowest > 0.0);
  const ColourInterval range = state.colourInterval();
  CAPTURE(range.low);
  CAPTURE(range.high);
  // [P10, P90] of K: inside [min, max] (the old +-P90 reached down to -P90, all of K on the red end).
  CHECK(range.oneSided());
  CHECK(range.low >= lowest);
  CHECK(range.high <= highest);
  CHECK(range.low < range.high);
  // The map still varies over the sphere: its lowest and highest K differ in colour, and both are
  // on the positive half of the paper's map (not blue).
  const glm::vec3 low = colorMapCpu(state.shading.colormap, lowest, range), high = colorMapCpu(state.shading.colormap, highest, range);
  CHECK(glm::length(low - high) > 0.5f);
  CHECK(low.z == 0.0f);
  CHECK(colourRangeNote(state).find("all K > 0: range") == 0);
  // Mixed signs keep the paper's map centred on zero: the mushroom's neck is negative.
  REQUIRE(session.document().loadMesh(shapes::mushroom(6), "mushroom"));
  settle(session);
  CHECK_FALSE(state.colourInterval().oneSided());
  CHECK(state.colourInterval().low == -state.colourInterval().high);
  CHECK(colourRangeNote(state).empty());
}

TEST_CASE("session: a pole zoom to rings m..m+2 raises the views to level m+2, or is refused, and a lower level ends it") {
  FakeWindow window;
  Session session(quiet(), window);
  ViewerState& state = session.state();
  REQUIRE(session.document().loadMesh(shapes::globe(8, 5), "globe"));
  state.views[0].level = 3;
  settle(session);
  // Rings 4..6 at level 3 did not exist: the view went blank. Now the level goes to 6.
  state.poleInspector.zoomRing = 4;
  settle(session);
  CHECK(state.poleInspector.zoomRing == 4);
  CHECK(state.views[0].level == 6);
  CHECK(state.views[0].status.shownLevel == 6);
  CHECK(state.notice.find("level 6 for the pole zoom") == 0);
  // A level under the zoom's rings ends it, saying why.
  state.views[0].level = 5;
  settle(session);
  CHECK(state.poleInspector.zoomRing == -1);
  CHECK(state.notice.find("pole zoom off: rings 4-6 need level 6") == 0);
  // Deeper than the scheme goes on this model: refused, the level stays.
  const int deepest = state.views[0].status.deepestLevel;
  state.poleInspector.zoomRing = deepest;
  settle(session);
  CHECK(state.poleInspector.zoomRing == -1);
  CHECK(state.views[0].level == 5);
  CHECK(state.notice.find("stops at level " + std::to_string(deepest)) != std::string::npos);
}
