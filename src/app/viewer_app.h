// The polarview viewer application: the window around a Session (session/session.h: state,
// document, surface cache, commands). ViewerApp owns the GLFW window, the ImGui context and the
// GPU objects: one PatchRenderer per surface a view shows or keeps parked, mirroring the cache.
// No globals: GLFW callbacks reach the app through glfwSetWindowUserPointer.
//
// Frame order (Dear ImGui's example): poll events, new frame, panels + input, queued commands,
// the session's update (loads, surfaces; finished ones uploaded), draw the views, overlay + UI, swap.
// Editing: a drag on a control vertex (pipeline/vertex_edit.h) changes the model's points; the same
// frame each view recomputes its kept refinement's points and patches and uploads them.
#pragma once

#include <array>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "app/gpu_mirror.h"
#include "render/framebuffer_capture.h"
#include "session/session.h"
#include "ui/input_events.h"
#include "ui/viewer_panels.h"
#include "pipeline/model.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"

struct GLFWwindow;

namespace polarview {

// The viewer's background colour (linear RGB); screenshots use it unless transparent.
constexpr float kBackground[3] = {0.17f, 0.18f, 0.20f};

class PatchRenderer;
class ShaderLibrary;

// The mouse as ImGui sees it (window coordinates, buttons left / right / middle), replacing the
// system pointer: for tests and `view --edit`, which drive the real input path without a person.
struct PointerState {
  float x = 0, y = 0;
  bool left = false, right = false, middle = false;
};

struct ViewerOptions {
  int width = 1600, height = 900;
  bool hidden = false;         // invisible window: batch rendering and tests
  bool persistRecent = true;   // keep recent files in ~/.config/polarview/recent.txt
  bool vsync = true;
  size_t faceBudget = kDefaultFaceBudget;
  // While the active view is idle, make its next level's surface ahead (prepareLevel) when all
  // views' levels and it together fit one view's face budget: the key press that asks for it then
  // only uploads.
  bool prepareNextLevel = true;
  // Draw the shallowest level that looks the same but for levelOfDetailPixels across at each feature
  // (pipeline/level_of_detail.h): the frame cost stops growing once rings are below a pixel. Off:
  // every view draws the level it shows (render --full-draw, comparisons).
  bool levelOfDetail = true;
  double levelOfDetailPixels = 3.0;
  // Viewer commands ("level 7", "camera.frame": session/command_table.h) run in the first frame, in
  // order: `view --do`.
  std::vector<std::string> scriptedCommands;
};

class ViewerApp : public WindowServices {
 public:
  explicit ViewerApp(const ViewerOptions& options);
  ~ViewerApp();
  ViewerApp(const ViewerApp&) = delete;
  ViewerApp& operator=(const ViewerApp&) = delete;

  // Creates the window and GL context, loads glad, starts ImGui and the renderers.
  bool init(std::string* error);

  // The session and its parts (what the window shows; tests and commands drive it).
  Session& session() { return session_; }
  ViewerSettings& settings() { return session_.settings(); }
  const ViewerSettings& settings() const { return session_.settings(); }
  ViewerStatus& status() { return session_.status(); }
  const ViewerStatus& status() const { return session_.status(); }
  Notices& notices() { return session_.notices(); }
  const Notices& notices() const { return session_.notices(); }
  Document& document() { return session_.document(); }
  const Document& document() const { return session_.document(); }
  // What the views show (the document's operations: document(), document.h).
  const Model& model() const { return session_.model(); }
  uint64_t modelGeneration() const { return model().generation; }
  // Which surface view v shows now (model generation, scheme, level); nullptr before the first.
  const BuiltSurface* shownSurface(int v) const { return session_.surfaces().shown(v).get(); }
  // The pole markers the last frame drew (overlay coordinates), for tests.
  const std::vector<PoleMarker>& lastPoleMarkers() const { return lastPoleMarkers_; }
  const BuiltSurface* parkedSurface(int v) const { return session_.surfaces().parked(v).get(); }
  // View v's renderer (what is on the GPU), for tests.
  const PatchRenderer& renderer(int v) const { return gpu_->renderer(v); }

  // One iteration of the main loop.
  void runFrame();
  bool shouldClose() const;
  // True while a file loads, a refinement runs or a view waits for one.
  bool busy() const { return session_.busy(); }
  // Runs frames' updates until every view shows what its settings ask for (or failed). [blocks]
  void waitUntilIdle();

  // Views, labels and colour bar rendered offscreen at width x height (rendered at supersample x
  // that size and filtered down). Needs a finished frame (ImGui fonts).
  RgbaImage renderImage(int width, int height, int supersample, bool transparent);
  // Writes the next free polarview_NNNN.png in the current directory: the views as on screen (same
  // layout and cameras, the panel column left out); returns its path (empty and a notice on failure).
  std::string saveScreenshot();
  // The next frame sets the pivot of `pick.view` to the surface point under (pick.x, pick.y), as a
  // double-click does.
  void requestPivot(const PivotPick& pick) { pendingPivot_ = pick; }
  // The next frame also writes the whole window (panels included) to `path` as a PNG.
  void captureWindowNextFrame(const std::string& path) { windowCapturePath_ = path; }
  // From the next frame on, ImGui reads `pointer` instead of the system mouse (nullopt: the system
  // mouse again). Every gesture then runs as with a real mouse (picking, drags, orbiting).
  void overridePointer(std::optional<PointerState> pointer) { pointerOverride_ = pointer; }

  // View v as drawn now (its camera, its rectangle of the current layout), for picking and tests.
  ViewTransform viewTransform(int v) const;
  // The part of the window the views tile (window coordinates): right of the panel column.
  ScreenRect viewArea() const;
  // Points every view's camera (or the shared one) at the model so that all its control points
  // (and with them the limit surface) fit a view of the size of `viewRect` (nullptr: the window's
  // first view now) below its title, keeping the viewing direction.
  void frameModel(const ScreenRect* viewRect);
  GLFWwindow* window() const { return window_; }

  // [WindowServices]
  void frameModel() override { frameModel(nullptr); }
  void setClipboard(const std::string& text) override;
  std::string clipboard() override;
  void takeScreenshot() override { saveScreenshot(); }

 private:
  static void onDrop(GLFWwindow* window, int count, const char** paths);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  // Hands this frame's share of the queued input events to ImGui's GLFW backend.
  void replayInputEvents();
  // The session's surfaces, then the GPU mirror and the edit cost with its upload.
  void updateSurfaces();
  // [Editing] A press at (x, y) in view v: picks the control vertex there and starts dragging it.
  bool beginVertexDrag(int v, const ScreenRect& rect, float x, float y);
  void applyVertexDrag(const VertexDragEvent& drag, const std::vector<ScreenRect>& rects);
  // The control vertices to mark in the overlay (selected, under the cursor), per view.
  std::vector<VertexMarker> vertexMarkers(const std::vector<ScreenRect>& rects) const;
  std::vector<PointMarker> pointMarkers(const std::vector<ScreenRect>& rects) const;
  std::vector<glm::dvec3> zoomedRingPoints() const;
  ViewTransform viewTransform(int v, const ScreenRect& rect) const;
  void resolvePivot(const PivotPick& pick, const std::vector<ScreenRect>& rects, float pixelScale, int framebufferHeight);

  ViewerOptions options_;
  Session session_;
  ViewerSettings& settings_;  // session_'s
  ViewerStatus& status_;      // session_'s: the window adds the GPU's part, frame time, screenshots, picks
  ViewerInput input_;
  InputEventQueue inputEvents_;
  GLFWwindow* window_ = nullptr;
  bool imguiReady_ = false;
  bool framedOnce_ = false;
  int framedViewCount_ = 0;       // the layout the cameras were last framed for
  bool framedWithPanels_ = true;
  std::pair<float, float> framedAreaSize_{0.0f, 0.0f};
  int framesDrawn_ = 0;
  std::shared_ptr<ShaderLibrary> shaders_;
  std::unique_ptr<GpuMirror> gpu_;  // made by init (needs the GL context)
  std::string windowCapturePath_;
  std::string imguiIniPath_;  // ImGui keeps a pointer to it (ImGuiIO::IniFilename)
  std::optional<PivotPick> pendingPivot_;
  std::optional<PointerState> pointerOverride_;
  std::pair<double, double> eventCursor_{0.0, 0.0};  // the cursor as of the last event GLFW delivered
  std::optional<std::pair<float, float>> buttonPosition_;  // where this frame's mouse button changed (window coordinates)
  std::vector<PoleMarker> lastPoleMarkers_;  // the last frame's (lastPoleMarkers)
};

}  // namespace polarview
