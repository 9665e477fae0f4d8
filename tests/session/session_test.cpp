// A whole viewer session without a window: commands load models, the surfaces follow, a failed
// load keeps the model, Ctrl+Z returns to the previous model, and saves and exports write files.
#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

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
