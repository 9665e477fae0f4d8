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
#include "ui/input_events.h"
#include "ui/viewer_panels.h"
#include "ui/viewer_state.h"

struct GLFWwindow;

namespace polarview {

// The viewer's background colour (linear RGB); screenshots use it unless transparent.
constexpr float kBackground[3] = {0.17f, 0.18f, 0.20f};

class PatchRenderer;
class ShaderLibrary;

// What one positions-only update of the shown views cost after control points moved (ms): the
// refinements' positions, patch extraction (with pole markers) and the upload, every view
// together (a surface two views share is updated once, uploaded twice).
struct EditCost {
  double positionsMs = 0.0, patchesMs = 0.0, uploadMs = 0.0, totalMs = 0.0;
  int views = 0;
};

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
  std::vector<std::string> scriptedCommands;  // `view --do`: viewer command ids run once the model is loaded
};

class ViewerApp {
 public:
  explicit ViewerApp(const ViewerOptions& options);
  ~ViewerApp();
  ViewerApp(const ViewerApp&) = delete;
  ViewerApp& operator=(const ViewerApp&) = delete;

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
  bool loading() const { return loadJob_.valid(); }
  // Shows `mesh` (validated here; false with the error in the state when it is not usable).
  bool loadMesh(PolyMesh mesh, const std::string& name, const std::string& path = "");
  // assets/default.obj, or the generated mushroom when the asset is missing.
  void loadDefaultModel();

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
  bool exporting() const { return exportJob_.valid(); }

  // The part of the window the views tile (window coordinates): right of the panel column.
  ScreenRect viewArea() const;
  // Points every view's camera (or the shared one) at the model so that all its control points
  // (and with them the limit surface) fit a view of the size of `viewRect` (nullptr: the window's
  // first view now) below its title, keeping the viewing direction.
  void frameModel(const ScreenRect* viewRect = nullptr);

  ViewerState& state() { return state_; }
  const ViewerState& state() const { return state_; }
  GLFWwindow* window() const { return window_; }
  // Bounding box of the current model's control points.
  glm::dvec3 modelMin() const { return modelMin_; }
  glm::dvec3 modelMax() const { return modelMax_; }
  // Which surface view v shows now (model generation, scheme, level); nullptr before the first.
  const BuiltSurface* shownSurface(int v) const { return views_[size_t(v)].shown.get(); }
  const BuiltSurface* parkedSurface(int v) const { return views_[size_t(v)].parked.get(); }
  // View v's renderer (what is on the GPU), for tests.
  const PatchRenderer& renderer(int v) const { return *views_[size_t(v)].renderer; }
  uint64_t modelGeneration() const { return model_.generation; }
  const Model& model() const { return model_; }

 private:
  struct ViewRuntime {
    std::unique_ptr<PatchRenderer> renderer;
    std::shared_ptr<const BuiltSurface> shown;
    // The surface this view showed before its scheme changed, still on the GPU in its own
    // renderer: toggling back swaps the two (no refinement, no upload). Dropped when the model or
    // its points change, or when memory is wanted (parkedFaces counts it against the budget).
    std::unique_ptr<PatchRenderer> parkedRenderer;
    std::shared_ptr<const BuiltSurface> parked;
    // What the renderer draws in place of `shown` where its deeper levels are below a pixel (a
    // shallower set of the same hierarchy; null: `shown` itself), and the parked renderer's.
    std::shared_ptr<const BuiltSurface> drawn, parkedDrawn;
    // The surface of the level shown before the last level step (same model, scheme and points):
    // a step back shows it again (an upload of what the GPU does not hold, nothing built). Counted
    // and dropped as the parked one.
    std::shared_ptr<const BuiltSurface> previousLevel;
    SurfaceJob job;
    std::optional<SurfaceKey> failed;  // last key that failed or was refused (not retried)
    std::optional<SurfaceKey> refreshFailed;  // a positions-only update failed here: rebuild instead
    std::future<bool> prepare;  // the next level made ahead (prepareLevel), if running
    std::optional<SurfaceKey> prepareFailed;  // a key prepareLevel could not make (not retried)
    SurfaceKey preparing;                     // the key of the running (or last) prepare
    int zoomShown = -1;         // the pole zoom ring the renderer holds (-1: the whole surface)
    double uploadMs = 0.0;  // the last show(): packing + upload
    size_t keptPatches = 0;  // patches of it that stayed on the GPU
    bool unparked = false;   // shown by unpark: nothing was built for it this time
    bool reshown = false;    // the previous level's surface shown again: nothing built, uploaded
  };

  // Frees a view's parked surface and its renderer's GPU buffers (needs the GL context).
  static void dropParked(ViewRuntime& view);
  static void onDrop(GLFWwindow* window, int count, const char** paths);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  // Hands this frame's share of the queued input events to ImGui's GLFW backend.
  void replayInputEvents();
  // Shows an already checked mesh (bumps the model generation, frames it).
  void adoptMesh(PolyMesh mesh, const std::string& name, const std::string& path);
  void loadFailed(const std::string& path, const std::string& error);
  // Ctrl+Z: shows the model replaced last (Open, Default model, a drop); again to redo.
  void undoModelReplacement();
  // Opens entry `index` (wrapping) of the dropped-files list.
  void openPlaylistEntry(int index);
  // Takes a finished background load (if any) and starts the queued one.
  void pollLoad();
  void processRequests();
  // Clears a notice kNoticeLifetime after it appeared (a newer one restarts the clock).
  void expireNotice();
  void updateSurfaces();
  // The pole inspector: its pole list on a model change; while its section is open, the
  // inspections of the selected pole for the visible views' schemes, computed in the background.
  void updatePoleInspector();
  // The Spectrum panel's eigenvalue lines, when it is open and the valence changed.
  void updateSpectrum();
  // Starts making view v's next level ahead when it is the active view and idle
  // (ViewerOptions::prepareNextLevel).
  void prepareNextLevel(int v, const SurfaceKey& wanted);
  // Keeps view v's shown surface (and its renderer) when `next` replaces it with another scheme's
  // surface of the same model and points, within the budget, so a toggle back is a swap.
  void parkShown(int v, const BuiltSurface& next);
  // The faces of the surfaces the visible views show (estimatedLevelFaces of their patch levels).
  size_t shownFaces() const;
  // Shows view v's parked surface again (swapping renderers); false when it is not `wanted`.
  bool unpark(int v, const SurfaceKey& wanted);
  // Faces of the refinements the views keep parked (every level their hierarchies made) or as their
  // previous level (estimatedLevelFaces), against the budget.
  size_t parkedFaces() const;
  // estimatedLevelFaces of `scheme` at `level` on the model, under this viewer's face budget.
  size_t levelFaces(SchemeChoice scheme, int level) const;
  // Keeps view v's shown surface as its previous level when `next` is a level step of it (same
  // model, scheme and points), within the budget.
  void keepPreviousLevel(int v, const BuiltSurface& next);
  // Positions-only updates of the visible views whose surface has the model's topology but older
  // points (and, once no drag runs, fresh curvature samples); records the cost. [O(faces of all levels)]
  void refreshEditedViews();
  void show(int v, std::shared_ptr<const BuiltSurface> surface);
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
  void resetEdits();
  // Ctrl+S: the edited mesh as OBJ (atomic; a failure leaves no file and shows one line).
  void saveEditedMesh();
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
  SurfaceKey wantedKey(int v) const;

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
  std::array<ViewRuntime, kMaxViews> views_;
  Model model_;
  Model previousModel_;       // the model before the last replacement (Ctrl+Z)
  std::string previousPath_;  // its file (empty for generated models)
  glm::dvec3 modelMin_{-1.0}, modelMax_{1.0};
  uint64_t colourRangeSignature_ = 0;
  std::vector<double> colourValues_, colourWeights_;  // samples of the shown views, by area
  std::pair<double, double> histogramRange_{0.0f, 0.0f};
  std::future<LoadedModel> loadJob_;
  std::optional<std::string> queuedLoad_;
  std::string windowCapturePath_;
  std::string imguiIniPath_;  // ImGui keeps a pointer to it (ImGuiIO::IniFilename)
  std::optional<PivotPick> pendingPivot_;
  std::future<std::vector<PoleInspection>> inspectJob_;
  std::string inspectRunning_, inspectShown_;  // what the job computes / what the panel shows
  uint64_t inspectPolesOf_ = 0;                // model generation the pole list is of
  std::optional<PointerState> pointerOverride_;
  std::pair<double, double> eventCursor_{0.0, 0.0};  // the cursor as of the last event GLFW delivered
  std::optional<std::pair<float, float>> buttonPosition_;  // where this frame's mouse button changed (window coordinates)
  ControlMeshEditor editor_;
  int movedVertices_ = 0;  // editor_.movedVertexCount(), counted when points change
  std::vector<EditCost> editCosts_;
  std::future<std::string> exportJob_;  // the notice to show when done; throws on failure
  std::string exportTarget_;
  static constexpr std::chrono::seconds kNoticeLifetime{8};
  std::string shownNotice_;
  std::chrono::steady_clock::time_point noticeSince_;
};

}  // namespace polarview
