// The polarview viewer application: one ViewerApp object owns the window, the ImGui context, one
// PatchRenderer per view and the background refinement jobs. No globals: GLFW callbacks reach the
// app through glfwSetWindowUserPointer.
//
// Frame order (Dear ImGui's example): poll events, new frame, panels + input, requests, rebuild
// what is dirty (finished jobs are uploaded, new jobs started), draw the views, overlay + UI, swap.
// Editing: a drag on a control vertex (pipeline/vertex_edit.h) changes the model's points; the same frame
// each view recomputes its kept refinement's points and patches (refreshSurface) and uploads them.
#pragma once

#include <array>
#include <chrono>
#include <future>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "pipeline/vertex_edit.h"
#include "pipeline/surface_pipeline.h"
#include "render/framebuffer_capture.h"
#include "session/background_job.h"
#include "session/command_table.h"
#include "session/surface_cache.h"
#include "ui/input_events.h"
#include "ui/viewer_panels.h"
#include "session/viewer_state.h"

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

// `polarview` / `polarview view FILE.obj`: opens the viewer (empty path: the default model).
int runViewer(const std::string& objPathOrEmpty);
// `polarview view [FILE.obj] [--frames N --stats] [--scheme a,b] [--level L] [--size WxH]`:
// the arguments after "view". With --frames it runs N frames and prints frame times as JSON.
int runViewerCommand(const std::vector<std::string>& args);
// `polarview render ...`: the arguments after "render"; 0 ok, 1 bad input ("polarview: FILE:LINE:
// msg" on stderr, no output file), 2 usage.
int runRenderCommand(const std::vector<std::string>& args);

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
};

class ViewerApp : public CommandHost {
 public:
  explicit ViewerApp(const ViewerOptions& options);
  ~ViewerApp();
  ViewerApp(const ViewerApp&) = delete;
  ViewerApp& operator=(const ViewerApp&) = delete;

  // [CommandHost] What the command table's commands ask of the viewer.
  void openFile(const std::string& path) override { requestLoad(path); }
  void reloadModel() override;
  void loadDefaultModel() override;
  void undoModelReplacement() override;
  void undo() override;
  void redo() override { redoEdit(); }
  void resetEdits() override;
  void saveEditedMesh() override;
  void exportSurface(bool bezierView) override { startExport(bezierView); }
  void openPlaylistEntry(int index) override;
  void convertToPolar(bool pentagons) override;
  void showEigenvector() override;
  void frameModel() override { frameModel(nullptr); }
  void setClipboard(const std::string& text) override;
  std::string clipboard() override;
  void takeScreenshot() override { saveScreenshot(); }

  // Creates the window and GL context, loads glad, starts ImGui and the renderers.
  bool init(std::string* error);

  // Loads an OBJ now (blocks; the command line uses it); on failure the message goes to
  // state().file.error, the model stays, false.
  bool loadFile(const std::string& path);
  // Starts reading and checking an OBJ on a worker thread; the window keeps running and the current
  // model stays until the new one is ready (a failure leaves it and shows the error). A request
  // while one runs replaces any queued one: the last request wins.
  void requestLoad(const std::string& path);
  // What a drop of files on the window does (the GLFW drop callback calls it): loads the first.
  void dropFiles(int count, const char* const* paths);
  // True while a requested file is being read.
  bool loading() const { return loadJob_.running(); }
  // Shows `mesh` (validated here; false with the error in the state when it is not usable).
  bool loadMesh(PolyMesh mesh, const std::string& name, const std::string& path = "");
  // (loadDefaultModel: assets/default.obj, or the generated mushroom when the asset is missing.)

  // One iteration of the main loop.
  void runFrame();
  bool shouldClose() const;
  // True while a file loads, a refinement runs or a view waits for one.
  bool busy() const;
  // Runs frames until every view shows what its settings ask for (or failed). [blocks]
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

  // [Editing] The base control mesh's points as edited, the selection and the history.
  const ControlMeshEditor& editor() const { return editor_; }
  // View v as drawn now (its camera, its rectangle of the current layout), for picking and tests.
  ViewTransform viewTransform(int v) const;
  // Every positions-only update since the model was loaded (the last 10000).
  const std::vector<EditCost>& editCosts() const { return editCosts_; }
  // True while a save or export runs in the background.
  bool exporting() const { return exportJob_.running(); }

  // The part of the window the views tile (window coordinates): right of the panel column.
  ScreenRect viewArea() const;
  // Points every view's camera (or the shared one) at the model so that all its control points
  // (and with them the limit surface) fit a view of the size of `viewRect` (nullptr: the window's
  // first view now) below its title, keeping the viewing direction.
  void frameModel(const ScreenRect* viewRect);

  ViewerState& state() { return state_; }
  const ViewerState& state() const { return state_; }
  GLFWwindow* window() const { return window_; }
  // Bounding box of the current model's control points.
  glm::dvec3 modelMin() const { return modelMin_; }
  glm::dvec3 modelMax() const { return modelMax_; }
  // Which surface view v shows now (model generation, scheme, level); nullptr before the first.
  const BuiltSurface* shownSurface(int v) const { return surfaces_.shown(v).get(); }
  const BuiltSurface* parkedSurface(int v) const { return surfaces_.parked(v).get(); }
  // View v's renderer (what is on the GPU), for tests.
  const PatchRenderer& renderer(int v) const { return *gpu_[size_t(v)].shown.renderer; }
  uint64_t modelGeneration() const { return model_.generation; }
  const Model& model() const { return model_; }

 private:
  // The GPU mirror of the surface cache: a renderer holding what a surface draws (its patches, or
  // the shallower set `drawn` where deeper rings are below a pixel, or a pole zoom's rings).
  struct GpuSlot {
    std::unique_ptr<PatchRenderer> renderer;
    std::shared_ptr<const BuiltSurface> surface, drawn;
    int zoom = -1;  // the pole zoom ring it holds (-1: the whole surface)
  };
  // Per view: the shown surface's renderer and the parked one's (a scheme toggle back swaps them).
  struct GpuView {
    GpuSlot shown, parked;
    double uploadMs = 0.0;   // the last upload of the shown surface: packing + upload
    size_t keptPatches = 0;  // patches of it that stayed on the GPU
  };
  // Brings view v's GPU mirror to the cache's shown and parked surfaces: swaps, drops or uploads.
  // Returns the milliseconds an upload took (0 when none). [O(patches not on the GPU)]
  double syncGpu(int v);
  std::unique_ptr<PatchRenderer> makeRenderer() const;
  static void onDrop(GLFWwindow* window, int count, const char** paths);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  // Hands this frame's share of the queued input events to ImGui's GLFW backend.
  void replayInputEvents();
  // Shows an already checked mesh (bumps the model generation, frames it).
  void adoptMesh(PolyMesh mesh, const std::string& name, const std::string& path);
  void loadFailed(const std::string& path, const std::string& error);
  // Takes a finished background load (if any) and starts the queued one.
  void pollLoad();
  // Clears a notice kNoticeLifetime after it appeared (a newer one restarts the clock).
  void expireNotice();
  void updateSurfaces();
  // The pole inspector: its pole list on a model change; while its section is open, the
  // inspections of the selected pole for the visible views' schemes, computed in the background.
  void updatePoleInspector();
  // The Spectrum panel's eigenvalue lines, when it is open and the valence changed.
  void updateSpectrum();
  // Uploads `surface`'s patches to view v's renderer (a pole zoom: its zoomed rings): the time it
  // took and the patches that stayed on the GPU. [O(patches not on the GPU)]
  struct UploadCost {
    double milliseconds = 0.0;
    size_t keptPatches = 0;
  };
  UploadCost upload(int v, const BuiltSurface& surface);
  // Draws the level levelToDraw picks for the view's camera (viewport `pixelsHigh` high): switches
  // `drawn` when it changes. [O(features) a frame; O(patches of the set) on a switch]
  void updateDrawnLevel(int v, double pixelsHigh);
  // [Editing] A press at (x, y) in view v: picks the control vertex there and starts dragging it.
  bool beginVertexDrag(int v, const ScreenRect& rect, float x, float y);
  void applyVertexDrag(const VertexDragEvent& drag, const std::vector<ScreenRect>& rects);
  // The editor's points become the model's (same faces, new points revision); the views follow in
  // refreshEditedViews.
  void commitEditedPoints();
  void undoEdit();
  void redoEdit();
  // Export .bv / refined control mesh of the active view, written on a worker thread.
  void startExport(bool bezierView);
  void pollExport();
  // The control vertices to mark in the overlay (selected, under the cursor), per view.
  std::vector<VertexMarker> vertexMarkers(const std::vector<ScreenRect>& rects) const;
  // Fills state_.edit: selection, history, default output paths.
  void updateEditState();
  ViewTransform viewTransform(int v, const ScreenRect& rect) const;
  void updateColourRange();
  // The curvature samples of the shown views (mode K or H) and the automatic ranges from them.
  void collectColourSamples();
  // Draws the views into the bound framebuffer; returns the pole markers the surfaces leave visible
  // (overlay coordinates: framebuffer pixels / pixelScale, y down).
  std::vector<PoleMarker> drawViews(const std::vector<ScreenRect>& rects, float pixelScale, int framebufferHeight);
  void resolvePivot(const PivotPick& pick, const std::vector<ScreenRect>& rects, float pixelScale, int framebufferHeight);
  void rememberRecent(const std::string& path);
  void loadRecent();

  ViewerOptions options_;
  ViewerState state_;
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
  SurfaceCache surfaces_;
  std::array<GpuView, kMaxViews> gpu_;
  Model model_;
  Model previousModel_;       // the model before the last replacement (Ctrl+Z)
  std::string previousPath_;  // its file (empty for generated models)
  glm::dvec3 modelMin_{-1.0}, modelMax_{1.0};
  uint64_t colourRangeSignature_ = 0;
  std::vector<double> colourValues_, colourWeights_;  // samples of the shown views, by area
  std::pair<double, double> histogramRange_{0.0f, 0.0f};
  BackgroundJob<LoadedModel> loadJob_;
  std::optional<std::string> queuedLoad_;
  std::string windowCapturePath_;
  std::string imguiIniPath_;  // ImGui keeps a pointer to it (ImGuiIO::IniFilename)
  std::optional<PivotPick> pendingPivot_;
  BackgroundJob<std::vector<PoleInspection>> inspectJob_;
  std::string inspectRunning_, inspectShown_;  // what the job computes / what the panel shows
  uint64_t inspectPolesOf_ = 0;                // model generation the pole list is of
  std::optional<PointerState> pointerOverride_;
  std::pair<double, double> eventCursor_{0.0, 0.0};  // the cursor as of the last event GLFW delivered
  std::optional<std::pair<float, float>> buttonPosition_;  // where this frame's mouse button changed (window coordinates)
  ControlMeshEditor editor_;
  int movedVertices_ = 0;  // editor_.movedVertexCount(), counted when points change
  std::vector<EditCost> editCosts_;
  BackgroundJob<std::string> exportJob_;  // the notice to show when done; throws on failure
  std::string exportTarget_;
  static constexpr std::chrono::seconds kNoticeLifetime{8};
  std::string shownNotice_;
  std::chrono::steady_clock::time_point noticeSince_;
};

}  // namespace polarview
