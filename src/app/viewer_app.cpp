// ViewerApp: window, frame loop, refinement jobs, drawing and screenshots (see viewer_app.h).
#include "app/viewer_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <glm/gtc/matrix_transform.hpp>

#include "app/export_command.h"
#include "core/mesh/ev_to_polar.h"
#include "core/subdiv/spectrum.h"
#include "core/subdiv/table_pool.h"
#include "pipeline/eigen_nets.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/refiner.h"
#include "render/gl_context.h"
#include "render/patch_renderer.h"
#include "render/shader_library.h"

namespace polarview {
namespace {

// [SECTION] Constants and helpers

constexpr size_t kMaxRecentFiles = 10;
constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

std::string recentFilePath() {
  const char* home = std::getenv("HOME");
  if (!home || !*home) return {};
  return std::string(home) + "/.config/polarview/recent.txt";
}

// Window coordinates (x, y in pixels, z the depth in [0, 1]) of `world`, and back, in double and
// relative to the eye: at a deep pole the points differ from the eye by 1e-6 of their coordinates,
// which float (glm::project's) would round away. `rotation`: the view matrix without translation.
glm::dvec3 windowOf(const glm::dvec3& world, const glm::dvec3& eye, const glm::dmat4& rotation, const glm::dmat4& proj,
                    const glm::dvec4& viewport) {
  const glm::dvec4 clip = proj * rotation * glm::dvec4(world - eye, 1.0);
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  return {viewport.x + (ndc.x + 1.0) * 0.5 * viewport.z, viewport.y + (ndc.y + 1.0) * 0.5 * viewport.w, (ndc.z + 1.0) * 0.5};
}
glm::dvec3 worldOf(const glm::dvec3& window, const glm::dvec3& eye, const glm::dmat4& rotation, const glm::dmat4& proj,
                   const glm::dvec4& viewport) {
  const glm::dvec4 ndc(2.0 * (window.x - viewport.x) / viewport.z - 1.0, 2.0 * (window.y - viewport.y) / viewport.w - 1.0,
                       2.0 * window.z - 1.0, 1.0);
  const glm::dvec4 fromEye = glm::inverse(proj * rotation) * ndc;
  return eye + glm::dvec3(fromEye) / fromEye.w;
}
glm::dmat4 rotationOf(const glm::mat4& view) { return glm::dmat4(glm::dmat3(glm::dmat4(view))); }

// Appends the poles the surface does not hide to `out`: each is projected into `view`, and kept when
// the depth buffer there (the surface just drawn) is not nearer the eye than the pole by more than
// `tolerance` (world units). A few poles per view, so one 1-pixel read each.
void visiblePoles(const std::vector<Point>& poles, const ViewParams& view, const glm::dvec3& eye, double tolerance,
                  float pixelScale, int framebufferHeight, std::vector<PoleMarker>* out) {
  constexpr size_t kMaxMarkers = 64;
  const glm::dvec4 viewport(view.viewport);
  const glm::dmat4 rotation = rotationOf(view.view), proj(view.proj);
  for (size_t i = 0; i < poles.size() && i < kMaxMarkers; ++i) {
    const glm::dvec3 window = windowOf(poles[i], eye, rotation, proj, viewport);
    int px = int(std::floor(window.x)), py = int(std::floor(window.y));
    if (!(window.z > 0.0 && window.z < 1.0) || px < view.viewport.x || py < view.viewport.y ||
        px >= view.viewport.x + view.viewport.z || py >= view.viewport.y + view.viewport.w) {
      continue;
    }
    const float depth = readDepthAt(px, py);
    if (depth < 1.0f) {
      const glm::dvec3 surface = worldOf({px + 0.5, py + 0.5, depth}, eye, rotation, proj, viewport);
      if (glm::length(surface - eye) < glm::length(poles[i] - eye) - tolerance) continue;  // hidden
    }
    out->push_back({float(window.x) / pixelScale, (float(framebufferHeight) - float(window.y)) / pixelScale});
  }
}

// Mixes a value into a running hash (to notice when the colour range inputs changed).
void hashMix(uint64_t& h, uint64_t value) { h = (h ^ value) * 1099511628211ull; }

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// A message for the one-line error field: line breaks become spaces.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

std::string absolutePath(const std::string& path) {
  std::error_code ignored;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ignored);
  return absolute.empty() ? path : absolute.lexically_normal().string();
}

std::string defaultModelAsset() { return std::string(POLARVIEW_ASSET_DIR) + "/default.obj"; }

constexpr size_t kMaxEditCosts = 10000;

}  // namespace

// [SECTION] Set-up and tear-down

ViewerApp::ViewerApp(const ViewerOptions& options) : options_(options) {}

ViewerApp::~ViewerApp() {
  // Jobs finish first (their futures block), then GL objects go while the context still exists.
  if (loadJob_.valid()) loadJob_.wait();
  if (exportJob_.valid()) exportJob_.wait();
  if (inspectJob_.valid()) inspectJob_.wait();
  for (ViewRuntime& view : views_) {
    view.job.wait();
    if (view.prepare.valid()) view.prepare.wait();
  }
  if (window_) {
    glfwMakeContextCurrent(window_);
    for (ViewRuntime& view : views_) {
      view.renderer.reset();
      dropParked(view);
    }
    shaders_.reset();
    if (imguiReady_) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    glfwDestroyWindow(window_);
  }
}

bool ViewerApp::init(std::string* error) {
  // GLFW and the window (hidden for batch work): GL 4.5 core, 4.1 accepted.
  glfwSetErrorCallback([](int code, const char* message) { std::fprintf(stderr, "polarview: GLFW error %d: %s\n", code, message); });
  if (!glfwInit()) {
    if (error) *error = "cannot initialise GLFW (no display? run under xvfb-run -a)";
    return false;
  }
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_VISIBLE, options_.hidden ? GLFW_FALSE : GLFW_TRUE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(options_.width, options_.height, "polarview", nullptr, nullptr);
  if (!window_) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    window_ = glfwCreateWindow(options_.width, options_.height, "polarview", nullptr, nullptr);
  }
  if (!window_) {
    if (error) *error = "cannot create a window with a GL 4.1+ core context";
    return false;
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(options_.vsync ? 1 : 0);
  if (!loadGlFunctions()) {
    if (error) *error = "cannot load GL 4.1+ functions (glad)";
    return false;
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, &ViewerApp::onDrop);
  // Keys, characters, buttons and the wheel go through the app's queue (ui/input_events.h), which
  // replays them to ImGui's backend one change per key a frame; focus and cursor-enter go straight.
  glfwSetKeyCallback(window_, &ViewerApp::onKey);
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int c) {
    if (auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(w)))
      app->inputEvents_.push({InputEvent::Kind::Char, int(c)});
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
    if (auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(w))) {
      InputEvent event{InputEvent::Kind::MouseButton, button, 0, action, mods};
      event.x = app->eventCursor_.first;  // where the cursor was when this event happened
      event.y = app->eventCursor_.second;
      app->inputEvents_.push(event);
    }
  });
  // The cursor in event order (glfwGetCursorPos answers for the time it is called, later).
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    if (auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(w))) app->eventCursor_ = {x, y};
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) {
    if (auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(w)))
      app->inputEvents_.push({InputEvent::Kind::Scroll, 0, 0, 0, 0, dx, dy});
  });
  glfwSetWindowFocusCallback(window_, ImGui_ImplGlfw_WindowFocusCallback);
  glfwSetCursorEnterCallback(window_, ImGui_ImplGlfw_CursorEnterCallback);

  // ImGui without its own callbacks (install_callbacks = false): the app feeds its backend.
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  // Window layout lives beside the recent files, not in whatever directory the viewer started in.
  if (!recentFilePath().empty()) imguiIniPath_ = std::filesystem::path(recentFilePath()).replace_filename("imgui.ini").string();
  io.IniFilename = options_.hidden || !options_.persistRecent || imguiIniPath_.empty() ? nullptr : imguiIniPath_.c_str();
  if (std::filesystem::exists(kFontPath)) io.Fonts->AddFontFromFileTTF(kFontPath, 15.0f);
  else io.Fonts->AddFontDefault();
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, false);
  ImGui_ImplOpenGL3_Init("#version 410");
  imguiReady_ = true;

  // One renderer per view over one shader library.
  shaders_ = std::make_shared<ShaderLibrary>();
  for (ViewRuntime& view : views_) {
    view.renderer = std::make_unique<PatchRenderer>();
    std::string log;
    if (!view.renderer->init(&log, shaders_)) {
      if (error) *error = "shaders: " + log;
      return false;
    }
  }
  state_.glInfo = currentGlVersion();
  if (options_.persistRecent) loadRecent();
  return true;
}

// [SECTION] Models and files

bool ViewerApp::loadFile(const std::string& path) {
  state_.file.pathField = path;
  LoadedModel loaded = readModelFile(path);
  if (!loaded.error.empty()) {
    loadFailed(path, loaded.error);
    return false;
  }
  adoptMesh(std::move(loaded.mesh), path, path);
  state_.file.warnings = std::move(loaded.warnings);
  return true;
}

void ViewerApp::requestLoad(const std::string& path) {
  state_.file.pathField = path;
  if (loadJob_.valid()) {
    queuedLoad_ = path;  // started when the running one is done; its result is then dropped
    return;
  }
  state_.file.loading = true;
  state_.file.loadingPath = path;
  loadJob_ = std::async(std::launch::async, [path] { return readModelFile(path); });
}

void ViewerApp::pollLoad() {
  if (!loadJob_.valid() || loadJob_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  LoadedModel loaded = loadJob_.get();
  state_.file.loading = false;
  state_.file.loadingPath.clear();
  if (queuedLoad_) {
    std::string next = std::move(*queuedLoad_);
    queuedLoad_.reset();
    requestLoad(next);
    return;
  }
  if (!loaded.error.empty()) {
    loadFailed(loaded.path, loaded.error);
    return;
  }
  adoptMesh(std::move(loaded.mesh), loaded.path, loaded.path);
  state_.file.warnings = std::move(loaded.warnings);
  state_.notice = "opened " + loaded.path;
}

void ViewerApp::loadFailed(const std::string& path, const std::string& error) {
  state_.file.error = error;
  state_.notice = "could not open " + path + " (the current model stays)";
}

void ViewerApp::dropFiles(int count, const char* const* paths) {
  if (count < 1 || !paths || !paths[0]) return;
  if (count > 1) {
    // Several files: open the first, keep all of them as a list to step through.
    state_.file.playlist.clear();
    for (int i = 0; i < count; ++i)
      if (paths[i]) state_.file.playlist.emplace_back(paths[i]);
    state_.file.playlistIndex = 0;
    state_.notice = "opening the first of " + std::to_string(count) + " dropped files (PageDown / PageUp for the others)";
  }
  requestLoad(paths[0]);
}

void ViewerApp::openPlaylistEntry(int index) {
  const std::vector<std::string>& list = state_.file.playlist;
  if (list.empty()) return;
  index = (index % int(list.size()) + int(list.size())) % int(list.size());
  state_.file.playlistIndex = index;
  requestLoad(list[size_t(index)]);
}

void ViewerApp::undoModelReplacement() {
  if (!previousModel_.mesh) {
    state_.notice = "nothing to undo";
    return;
  }
  // Swap back (a second Ctrl+Z redoes): the previous mesh is shown as a new model generation.
  Model previous = previousModel_;
  const std::string previousPath = previousPath_;
  adoptMesh(PolyMesh(*previous.mesh), previous.name, previousPath);
  state_.notice = "back to " + previous.name;
}

bool ViewerApp::loadMesh(PolyMesh mesh, const std::string& name, const std::string& path) {
  if (std::string error = checkModelMesh(mesh, name); !error.empty()) {
    state_.file.error = error;
    return false;
  }
  adoptMesh(std::move(mesh), name, path);
  return true;
}

void ViewerApp::adoptMesh(PolyMesh mesh, const std::string& name, const std::string& path) {
  modelMin_ = modelMax_ = mesh.points.front();
  for (const Point& p : mesh.points) {
    modelMin_ = glm::min(modelMin_, p);
    modelMax_ = glm::max(modelMax_, p);
  }
  state_.file.modelVertices = mesh.vertexCount();
  state_.file.modelFaces = mesh.faceCount();
  if (model_.mesh) {  // what Ctrl+Z returns to
    previousModel_ = model_;
    previousPath_ = state_.file.loadedPath;
    state_.file.previousModelName = model_.name;
  }
  model_ = makeModel(std::make_shared<const PolyMesh>(std::move(mesh)), name, model_.generation + 1);
  // Editing starts over: the loaded points are what Reset returns to.
  editor_.start(model_.mesh->points);
  movedVertices_ = 0;
  editCosts_.clear();
  state_.edit.error.clear();
  state_.file.modelName = name;
  state_.file.loadedPath = path;
  if (!path.empty()) state_.file.pathField = path;  // the field names what is shown (after Ctrl+Z too)
  state_.file.error.clear();
  state_.file.warnings.clear();
  for (ViewRuntime& view : views_) view.failed.reset();
  for (ViewStatus& status : state_.status) status.message.clear();
  if (!path.empty()) rememberRecent(path);
  frameModel();
}

void ViewerApp::loadDefaultModel() {
  std::string asset = std::string(POLARVIEW_ASSET_DIR) + "/default.obj";
  if (std::filesystem::exists(asset) && loadFile(asset)) {
    state_.file.modelName = "default: " + asset;
    return;
  }
  loadMesh(shapes::mushroom(12), "default: mushroom (generated, n = 12)");
}

void ViewerApp::rememberRecent(const std::string& path) {
  std::vector<std::string>& recent = state_.file.recent;
  std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
  recent.erase(std::remove(recent.begin(), recent.end(), absolute), recent.end());
  recent.insert(recent.begin(), absolute);
  if (recent.size() > kMaxRecentFiles) recent.resize(kMaxRecentFiles);
  if (!options_.persistRecent) return;
  std::string file = recentFilePath();
  if (file.empty()) return;
  std::error_code ignored;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ignored);
  std::ofstream out(file);
  for (const std::string& p : recent) out << p << '\n';
}

void ViewerApp::loadRecent() {
  std::ifstream in(recentFilePath());
  std::string line;
  while (std::getline(in, line) && state_.file.recent.size() < kMaxRecentFiles) {
    if (!line.empty()) state_.file.recent.push_back(line);
  }
}

void ViewerApp::onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(window));
  if (!app) return;
  // Shortcuts take every press at once (their own queue); ImGui gets the event trickled.
  if (action == GLFW_PRESS) app->input_.queueKeyPress(key, mods);
  app->inputEvents_.push({InputEvent::Kind::Key, key, scancode, action, mods});
}

void ViewerApp::replayInputEvents() {
  for (const InputEvent& e : inputEvents_.takeFrame()) {
    switch (e.kind) {
      case InputEvent::Kind::Key: ImGui_ImplGlfw_KeyCallback(window_, e.code, e.scancode, e.action, e.mods); break;
      case InputEvent::Kind::Char: ImGui_ImplGlfw_CharCallback(window_, unsigned(e.code)); break;
      case InputEvent::Kind::MouseButton:
        ImGui_ImplGlfw_MouseButtonCallback(window_, e.code, e.action, e.mods);
        buttonPosition_ = std::pair{float(e.x), float(e.y)};
        break;
      case InputEvent::Kind::Scroll: ImGui_ImplGlfw_ScrollCallback(window_, e.dx, e.dy); break;
    }
  }
  // A double-click's two presses now reach ImGui at least two frames apart: allow for slow frames.
  ImGuiIO& io = ImGui::GetIO();
  io.MouseDoubleClickTime = std::max(0.30f, 2.5f * io.DeltaTime);
}

void ViewerApp::onDrop(GLFWwindow* window, int count, const char** paths) {
  auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(window));
  if (app) app->dropFiles(count, paths);
}

ScreenRect ViewerApp::viewArea() const {
  int width = options_.width, height = options_.height;
  if (window_) glfwGetWindowSize(window_, &width, &height);
  const float panel = std::min(panelColumnWidth(state_), float(width) * 0.5f);
  return ScreenRect{panel, 0, std::max(float(width) - panel, 1.0f), std::max(float(height), 1.0f)};
}

void ViewerApp::frameModel(const ScreenRect* viewRect) {
  const ScreenRect view =
      viewRect ? *viewRect : layoutViews(state_.viewCount, viewArea(), colourBarReserve(state_, 1.0f)).front();
  const double aspect = double(view.w) / std::max(double(view.h), 1.0);
  // Keep the model out from under the view's title (a strip at the top; symmetric, so centred).
  const double heightFraction = std::max(0.5, 1.0 - 2.0 * double(viewTitleHeight(1.0f)) / std::max(double(view.h), 1.0));
  auto frameCamera = [&](OrbitCamera& camera) {
    if (model_.mesh) camera.framePoints(model_.mesh->points.data(), model_.mesh->points.size(), aspect, heightFraction);
    else camera.frame(modelMin_, modelMax_, aspect);
  };
  if (state_.linkCameras) {
    frameCamera(state_.sharedCamera);
  } else {
    for (ViewSettings& view : state_.views) frameCamera(view.camera);
  }
  framedOnce_ = true;
  framedViewCount_ = state_.viewCount;
  framedWithPanels_ = state_.showPanels;
  const ScreenRect area = viewArea();
  framedAreaSize_ = {area.w, area.h};
}

// [SECTION] Requests from panels and hotkeys

void ViewerApp::processRequests() {
  ViewerRequests& r = state_.requests;
  if (r.load) requestLoad(state_.file.pathField);
  if (r.reload) {
    if (state_.file.loadedPath.empty()) loadDefaultModel();
    else requestLoad(state_.file.loadedPath);
  }
  if (r.loadDefault) loadDefaultModel();
  if (r.undoModel) undoModelReplacement();
  // Ctrl+Z undoes vertex drags first; with none left it goes back to the previous model.
  if (r.undo) {
    if (editor_.undoCount() > 0) undoEdit();
    else undoModelReplacement();
  }
  if (r.redo) redoEdit();
  if (r.resetEdits) resetEdits();
  if (r.showEigenvector) {
    const SpectrumSettings& spectrum = state_.spectrum;
    try {
      const std::string name = "RTS eigenvector v" + std::to_string(spectrum.k) + ", valence " + std::to_string(spectrum.valence) +
                               (spectrum.c2psSteps > 0 ? ", " + std::to_string(spectrum.c2psSteps) + " C2PS steps" : "");
      if (loadMesh(eigenNet(spectrum.valence, spectrum.k, spectrum.c2psSteps), name, ""))
        state_.notice = name + " (Ctrl+Z returns)";
    } catch (const std::exception& e) {
      state_.notice = std::string("eigenvector: ") + e.what();
    }
  }
  if (r.convertToPolar && model_.mesh) {
    try {
      PolarConversion conversion = convertExtraordinaryToPolar(*model_.mesh, r.convertWithPentagons, model_.name);
      if (conversion.converted.empty()) {
        state_.notice = "no extraordinary vertex to convert (interior, all quads around it, valence != 4)";
      } else {
        const size_t count = conversion.converted.size();
        const std::string name = "converted (Fig. 14" + std::string(r.convertWithPentagons ? "c" : "a") + "): " + model_.name;
        if (loadMesh(std::move(conversion.mesh), name, ""))
          state_.notice = std::to_string(count) + " extraordinary vertices made poles (Ctrl+Z returns)";
      }
    } catch (const std::exception& e) {
      state_.notice = std::string("conversion failed: ") + e.what();
    }
  }
  if (r.saveEdited) saveEditedMesh();
  if (r.exportBezierView) startExport(true);
  if (r.exportRefinedMesh) startExport(false);
  if (r.playlistStep != 0) openPlaylistEntry(state_.file.playlistIndex + r.playlistStep);
  if (r.playlistPick >= 0) openPlaylistEntry(r.playlistPick);
  if (r.frame) frameModel();
  if (r.preset) {
    // A preset turns the cameras and shows the whole model again (from a close-up too).
    for (int v = 0; v < kMaxViews; ++v) state_.camera(v).applyPreset(*r.preset);
    frameModel();
  }
  OrbitCamera& active = state_.camera(state_.activeView);
  if (r.copyCamera) {
    std::string json = cameraToJson(active);
    glfwSetClipboardString(window_, json.c_str());
    state_.notice = "camera copied: " + json;
  }
  if (r.pasteCamera) {
    const char* text = glfwGetClipboardString(window_);
    std::string error;
    std::optional<OrbitCamera> camera = cameraFromJson(text ? text : "", active, &error);
    if (camera) {
      active = *camera;
      state_.notice = "camera pasted";
    } else {
      state_.notice = error;
    }
  }
  bool screenshot = r.screenshot;
  r = ViewerRequests{};
  if (screenshot) saveScreenshot();
}

// [SECTION] Rebuilding what is dirty

SurfaceKey ViewerApp::wantedKey(int v) const {
  return SurfaceKey{model_.generation, state_.views[size_t(v)].scheme, state_.views[size_t(v)].level, model_.points};
}

ViewerApp::UploadCost ViewerApp::upload(int v, const BuiltSurface& surface) {
  ViewRuntime& view = views_[size_t(v)];
  // A level step on the same hierarchy keeps the patches both levels share on the GPU.
  const auto start = std::chrono::steady_clock::now();
  const int zoom = state_.poleInspector.zoomRing;
  if (zoom >= 0 && !surface.poles.empty()) {
    // Pole zoom: the rings of the inspected pole, scaled in double (a new upload: no stable prefix).
    const int pole = std::clamp(state_.poleInspector.pole, 0, int(surface.poles.size()) - 1);
    view.renderer->setPatches(zoomAboutPole(surface.patches, pole, zoom, 3, surface.poles[size_t(pole)]));
    view.zoomShown = zoom;
  } else {
    view.renderer->setPatches(surface.patches, surface.stamp, surface.regularCount);
    view.zoomShown = -1;
  }
  return {millisecondsSince(start), view.renderer->lastReusedPatches()};
}

void ViewerApp::show(int v, std::shared_ptr<const BuiltSurface> surface) {
  ViewRuntime& view = views_[size_t(v)];
  const UploadCost cost = upload(v, *surface);
  view.uploadMs = cost.milliseconds;  // the Stats panel's: a level-of-detail switch does not count
  view.keptPatches = cost.keptPatches;
  view.drawn.reset();  // the level of detail is picked again for the new surface
  view.unparked = view.reshown = false;
  view.renderer->setControlMesh(surface->controlMesh, surface->netSegments);
  view.renderer->setPoleMarkers(surface->poles);
  view.shown = std::move(surface);
}

void ViewerApp::updateDrawnLevel(int v, double pixelsHigh) {
  ViewRuntime& view = views_[size_t(v)];
  const BuiltSurface* shown = view.shown.get();
  if (!shown || view.zoomShown >= 0) return;
  // While a drag moves points every frame the full set is drawn (each new set would be assembled anew).
  int wanted = shown->patchLevel;
  if (options_.levelOfDetail && !state_.edit.dragging && shown->key.points == model_.points)
    wanted = levelToDraw(shown->detail, shown->patchLevel, state_.camera(v), pixelsHigh, options_.levelOfDetailPixels);
  const int drawnNow = view.drawn ? view.drawn->patchLevel : shown->patchLevel;
  if (wanted != drawnNow) {
    std::shared_ptr<const BuiltSurface> drawn = wanted < shown->patchLevel ? drawnSurface(*shown, model_, wanted) : nullptr;
    if (wanted >= shown->patchLevel || drawn) {  // else not available now (an edit is applied): keep
      upload(v, drawn ? *drawn : *shown);
      view.drawn = std::move(drawn);
    }
  }
  ViewStatus& status = state_.status[size_t(v)];
  status.drawnLevel = view.drawn ? view.drawn->patchLevel : shown->patchLevel;
  status.drawnPatches = int(view.drawn ? view.drawn->patches.size() : shown->patches.size());
}

size_t ViewerApp::levelFaces(SchemeChoice scheme, int level) const {
  return estimatedLevelFaces(model_, scheme, level, options_.faceBudget);
}

size_t ViewerApp::parkedFaces() const {
  size_t faces = 0;
  for (const ViewRuntime& view : views_) {
    // A parked surface keeps its whole hierarchy: every level made, ahead ones too.
    if (const BuiltSurface* parked = view.parked.get())
      faces += levelFaces(parked->key.scheme,
                                   std::max(parked->patchLevel, parked->hierarchy ? parked->hierarchy->deepestMade.load() : 0));
    // The previous level shares the shown surface's hierarchy: its own patches (at most a level's).
    if (const BuiltSurface* previous = view.previousLevel.get())
      faces += levelFaces(previous->key.scheme, previous->patchLevel);
  }
  return faces;
}

size_t ViewerApp::shownFaces() const {
  size_t faces = 0;
  for (int w = 0; w < state_.viewCount; ++w)
    if (const BuiltSurface* shown = views_[size_t(w)].shown.get())
      faces += levelFaces(shown->key.scheme, shown->patchLevel);
  return faces;
}

void ViewerApp::dropParked(ViewRuntime& view) {
  view.parked.reset();
  view.parkedDrawn.reset();
  view.parkedRenderer.reset();  // its GPU buffers too
}

void ViewerApp::keepPreviousLevel(int v, const BuiltSurface& next) {
  ViewRuntime& view = views_[size_t(v)];
  const BuiltSurface* shown = view.shown.get();
  const bool step = shown && shown->key.model == next.key.model && shown->key.scheme == next.key.scheme &&
                    shown->key.points == next.key.points && shown->key.level != next.key.level;
  if (!step) return;
  view.previousLevel.reset();  // the older one goes first
  // Memory: every view's surface, the new one and the kept ones within the budget.
  if (parkedFaces() + shownFaces() + levelFaces(next.key.scheme, next.patchLevel) <= options_.faceBudget)
    view.previousLevel = view.shown;
}

void ViewerApp::parkShown(int v, const BuiltSurface& next) {
  ViewRuntime& view = views_[size_t(v)];
  if (!view.shown || view.shown->key.model != next.key.model || view.shown->key.points != next.key.points ||
      view.shown->key.scheme == next.key.scheme)
    return;
  dropParked(view);  // the older parked surface goes first (also when this one cannot be parked)
  // A zoomed renderer holds other patches than the surface's; memory as in keepPreviousLevel.
  if (view.zoomShown >= 0 ||
      parkedFaces() + shownFaces() + levelFaces(next.key.scheme, next.patchLevel) > options_.faceBudget)
    return;
  // The shown surface keeps its renderer; the new one goes to the other (made on first use).
  auto renderer = std::make_unique<PatchRenderer>();
  std::string log;
  if (!renderer->init(&log, shaders_)) return;  // not expected: the shaders compiled for the first one
  view.parkedRenderer = std::move(view.renderer);
  view.renderer = std::move(renderer);
  view.parked = std::move(view.shown);
  view.parkedDrawn = std::move(view.drawn);
}

bool ViewerApp::unpark(int v, const SurfaceKey& wanted) {
  ViewRuntime& view = views_[size_t(v)];
  if (!view.parked || view.parked->key != wanted || state_.poleInspector.zoomRing >= 0) return false;
  const auto start = std::chrono::steady_clock::now();
  std::swap(view.renderer, view.parkedRenderer);
  std::swap(view.shown, view.parked);  // the one shown so far is parked in turn
  std::swap(view.drawn, view.parkedDrawn);  // each renderer keeps what it draws
  if (view.parked && (view.zoomShown >= 0 || view.parked->key.model != wanted.model || view.parked->key.points != wanted.points))
    dropParked(view);
  view.zoomShown = -1;
  view.keptPatches = view.shown->patches.size();
  view.unparked = true;
  view.reshown = false;
  view.previousLevel.reset();  // of the other scheme
  view.uploadMs = millisecondsSince(start);
  return true;
}

void ViewerApp::refreshEditedViews() {
  EditCost cost;
  bool positionsMoved = false;
  // Each stale surface is refreshed once; views that shared it share the refreshed one.
  std::vector<std::pair<const BuiltSurface*, std::shared_ptr<const BuiltSurface>>> refreshed;
  for (int v = 0; v < state_.viewCount; ++v) {
    ViewRuntime& view = views_[size_t(v)];
    const SurfaceKey wanted = wantedKey(v);
    if (!view.shown || !view.shown->refinement || !view.shown->key.sameTopology(wanted)) continue;
    if (view.refreshFailed && *view.refreshFailed == wanted) continue;
    const bool pointsStale = view.shown->key.points != wanted.points;
    const bool samplesStale = !editor_.dragging() && view.shown->samples && view.shown->samples->points != wanted.points;
    if (!pointsStale && !samplesStale) continue;

    // Positions, patches and (once the drag is over) curvature samples on the kept hierarchy.
    const auto start = std::chrono::steady_clock::now();
    RefreshTiming timing;  // stays zero for a view sharing a surface refreshed for another
    std::shared_ptr<const BuiltSurface> surface;
    for (const auto& [old, fresh] : refreshed)
      if (old == view.shown.get()) surface = fresh;
    if (!surface) {
      try {
        surface = refreshSurface(*view.shown, model_, !editor_.dragging(), &timing);
      } catch (const std::exception& e) {
        // Not expected (the topology is the one it was built with); the view is rebuilt instead.
        view.refreshFailed = wanted;
        state_.status[size_t(v)].message = std::string("positions-only update failed (rebuilding): ") + e.what();
        continue;
      }
      refreshed.emplace_back(view.shown.get(), surface);
    }
    const auto uploadStart = std::chrono::steady_clock::now();
    show(v, surface);
    views_[size_t(v)].keptPatches = 0;  // moved points: no patch stayed (the Stats panel said "a level step")
    const double uploadMs = millisecondsSince(uploadStart);
    // The per-frame cost of moved points; retaking the curvature samples (once, at the end of a
    // drag, or with an undo) is not part of it.
    if (pointsStale) {
      positionsMoved = true;
      cost.positionsMs += timing.positionsMs;
      cost.patchesMs += timing.patchesMs;
      cost.uploadMs += uploadMs;
      cost.totalMs += millisecondsSince(start) - timing.samplesMs;
      ++cost.views;
    }
  }
  if (!positionsMoved) return;
  if (editCosts_.size() >= kMaxEditCosts) editCosts_.erase(editCosts_.begin());
  editCosts_.push_back(cost);
  state_.edit.positionsMs = cost.positionsMs;
  state_.edit.patchesMs = cost.patchesMs;
  state_.edit.uploadMs = cost.uploadMs;
  state_.edit.totalMs = cost.totalMs;
  state_.edit.updatedViews = cost.views;
}

void ViewerApp::updateSurfaces() {
  if (!model_.mesh) return;
  refreshEditedViews();
  for (int v = 0; v < kMaxViews; ++v) {
    ViewRuntime& view = views_[size_t(v)];
    ViewStatus& status = state_.status[size_t(v)];
    const bool visible = v < state_.viewCount;

    // A finished job: show it if it is still wanted, else drop it (a newer request follows). One
    // built from points edited since is shown too, then brought up to date by a positions-only
    // update (the next refreshEditedViews), so a long build is not thrown away by a drag.
    if (std::optional<SurfaceJob::Outcome> outcome = view.job.poll()) {
      if (!outcome->error.empty()) {
        view.failed = outcome->key;
        status.message = outcome->error;
      } else if (outcome->surface->key.sameTopology(wantedKey(v))) {
        parkShown(v, *outcome->surface);
        keepPreviousLevel(v, *outcome->surface);
        show(v, outcome->surface);
        status.message.clear();
      }
    }

    // The pole zoom changed: the same surface, other patches on the GPU.
    if (view.shown && view.zoomShown != (view.shown->poles.empty() ? -1 : state_.poleInspector.zoomRing)) show(v, view.shown);

    // A refused or failed key reverts the view to what it shows, so the controls tell the truth.
    SurfaceKey wanted = wantedKey(v);
    if (view.failed && *view.failed == wanted && view.shown && view.shown->key.model == wanted.model) {
      state_.views[size_t(v)].scheme = view.shown->key.scheme;
      state_.views[size_t(v)].level = view.shown->key.level;
      wanted = wantedKey(v);
    }

    // Start what the settings ask for: reuse another view's surface, else refine in the background.
    // A surface of this topology at older points waits for its positions-only update instead.
    // A parked surface of another model or older points, or of the scheme shown, is of no use.
    if (view.parked && (!visible || view.parked->key.model != model_.generation || view.parked->key.points != model_.points ||
                        (view.shown && view.shown->key.scheme == view.parked->key.scheme)))
      dropParked(view);
    if (view.previousLevel && (!visible || view.previousLevel->key.model != model_.generation ||
                               view.previousLevel->key.points != model_.points || !view.shown ||
                               view.shown->key.scheme != view.previousLevel->key.scheme))
      view.previousLevel.reset();
    const bool refreshable = view.shown && view.shown->refinement && view.shown->key.sameTopology(wanted) &&
                             !(view.refreshFailed && *view.refreshFailed == wanted);
    bool dirty = visible && (!view.shown || view.shown->key != wanted) && !refreshable &&
                 !(view.failed && *view.failed == wanted);
    if (dirty && !view.job.running()) {
      std::shared_ptr<const BuiltSurface> twin;
      for (const ViewRuntime& other : views_) {
        if (other.shown && other.shown->key == wanted) twin = other.shown;
      }
      if (unpark(v, wanted)) {
        status.message.clear();
      } else if (view.previousLevel && view.previousLevel->key == wanted && state_.poleInspector.zoomRing < 0) {
        // A step back to the level shown before: its surface again (the GPU keeps the shared patches).
        std::shared_ptr<const BuiltSurface> previous = std::move(view.previousLevel);
        view.previousLevel = view.shown;
        show(v, std::move(previous));
        view.reshown = true;
        status.message.clear();
      } else if (twin) {
        parkShown(v, *twin);
        show(v, twin);
      } else if (std::string refusal = checkFaceBudget(model_, wanted, options_.faceBudget); !refusal.empty()) {
        view.failed = wanted;
        status.message = refusal;
      } else {
        // The view's own hierarchy (same model and scheme) is stepped to the new level; so is its
        // parked one's (the parked surface goes: its hierarchy will be at another level).
        std::shared_ptr<SurfaceHierarchy> reusable;
        if (view.shown && view.shown->hierarchy && view.shown->key.model == wanted.model && view.shown->key.scheme == wanted.scheme)
          reusable = view.shown->hierarchy;
        else if (view.parked && view.parked->hierarchy && view.parked->key.model == wanted.model &&
                 view.parked->key.scheme == wanted.scheme)
          reusable = view.parked->hierarchy;
        if (view.parked && view.parked->hierarchy == reusable) dropParked(view);
        // Kept surfaces give their memory to a new refinement that would not fit beside them.
        const bool fits = parkedFaces() + shownFaces() +
                              levelFaces(wanted.scheme,
                                                  patchLevelFor(model_, wanted.scheme, wanted.level, options_.faceBudget)) <=
                          options_.faceBudget;
        if (!fits)
          for (ViewRuntime& other : views_) {
            dropParked(other);
            other.previousLevel.reset();
          }
        view.job.start(model_, wanted, options_.faceBudget, reusable);
      }
    }

    // Report.
    status.deepestLevel = deepestLevel(model_, state_.views[size_t(v)].scheme, options_.faceBudget);
    prepareNextLevel(v, wanted);
    status.levelLimit = levelRefusal(model_, state_.views[size_t(v)].scheme, status.deepestLevel + 1,
                                     options_.faceBudget);
    status.refining = view.job.running();
    status.refiningSeconds = status.refining ? view.job.runningSeconds() : 0.0;
    status.hasSurface = view.shown != nullptr;
    if (view.shown) {
      status.shownScheme = view.shown->key.scheme;
      status.shownLevel = view.shown->key.level;
      status.patchCount = int(view.shown->patches.size());
      status.patchesPerKind = view.shown->patchesPerKind;
      status.controlFaces = view.shown->controlMesh.faceCount();
      // A surface shown again from the park cost nothing to build this time.
      status.unparked = view.unparked;
      status.reshown = view.reshown;
      const bool built = !view.unparked && !view.reshown;
      status.refineMs = built ? view.shown->refineMs : 0.0;
      status.refineOnlyMs = built ? view.shown->refineOnlyMs : 0.0;
      status.patchesMs = built ? view.shown->patchesMs : 0.0;
      status.samplesMs = built ? view.shown->samplesMs : 0.0;
      status.uploadMs = view.uploadMs;
      status.patchLevel = view.shown->patchLevel;
      status.drawnLevel = view.drawn ? view.drawn->patchLevel : view.shown->patchLevel;
      status.drawnPatches = int(view.drawn ? view.drawn->patches.size() : view.shown->patches.size());
      status.zoomRing = view.zoomShown;
      status.keptPatches = int(view.keptPatches);
      status.polesByScheme = view.shown->polesByScheme;
      status.polesByCatmullClark = view.shown->polesByCatmullClark;
      status.fallbackReason = view.shown->fallbackReason;
    }
  }
}

void ViewerApp::updateColourRange() {
  // The curvature map some view shows (views may shade differently: render --shade a,b).
  const std::optional<ShadingParams::Mode> shown = state_.curvatureShade();
  if (!shown) return;
  const ShadingParams::Mode mode = *shown;
  uint64_t signature = 14695981039346656037ull;
  hashMix(signature, uint64_t(mode));
  hashMix(signature, uint64_t(state_.colour.quantile * 1e6f));
  // The samples, not the surfaces: a drag makes new surfaces every frame with the same samples.
  for (int v = 0; v < state_.viewCount; ++v)
    if (views_[size_t(v)].shown) hashMix(signature, uint64_t(uintptr_t(views_[size_t(v)].shown->samples.get())));
  if (signature != colourRangeSignature_) {
    colourRangeSignature_ = signature;
    collectColourSamples();
  }
  // The histogram follows the range the bar shows (typed or automatic).
  const std::pair<double, double> shownRange{state_.colourRangeBelow(), state_.colourRange()};
  if (shownRange != histogramRange_ || state_.colour.histogram.empty()) {
    histogramRange_ = shownRange;
    state_.colour.histogram = weightedHistogram(colourValues_, colourWeights_, shownRange.first, shownRange.second,
                                                kHistogramBins);
  }
}

void ViewerApp::collectColourSamples() {
  const ShadingParams::Mode mode = state_.curvatureShade().value_or(state_.shading.mode);
  // One range over the samples of every visible view, so equal colours mean equal values.
  // Each view counts by area: weights are normalised per view so a finer level does not outvote.
  std::vector<double>& values = colourValues_;
  std::vector<double>& weights = colourWeights_;
  values.clear();
  weights.clear();
  for (int v = 0; v < state_.viewCount; ++v) {
    if (!views_[size_t(v)].shown || !views_[size_t(v)].shown->samples) continue;
    const CurvatureSamples& s = *views_[size_t(v)].shown->samples;
    const std::vector<double>& samples = mode == ShadingParams::Mode::Gaussian ? s.gaussian : s.mean;
    double area = 0.0;
    for (double a : s.areas) area += a;
    if (!(area > 0.0)) continue;
    values.insert(values.end(), samples.begin(), samples.end());
    for (double a : s.areas) weights.push_back(a / area);
  }
  if (values.empty()) return;
  state_.colour.autoRange = weightedSymmetricRange(values, weights, state_.colour.quantile);
  // Each side apart, for the asymmetric range; a side without values keeps a sliver of the other.
  const double low = weightedPercentile(values, weights, 1.0 - state_.colour.quantile);
  const double high = weightedPercentile(values, weights, state_.colour.quantile);
  const double floor = 1e-3 * state_.colour.autoRange;
  state_.colour.autoBelow = std::max(-low, floor);
  state_.colour.autoAbove = std::max(high, floor);
  state_.colour.histogram.clear();  // recomputed for the new samples
}

void ViewerApp::updateSpectrum() {
  SpectrumSettings& spectrum = state_.spectrum;
  const bool open = spectrum.open;
  spectrum.open = false;  // the panel marks it again next frame while the section is open
  if (!open || spectrum.linesValence == spectrum.valence) return;
  // Small (6n x 6n, n <= 24): computed on the GL thread when the valence changes.
  spectrum.lines.clear();
  try {
    const std::vector<EigenPair> pairs = schemeEigenPairs(Scheme::RTS, spectrum.valence, 8);
    for (size_t k = 0; k < pairs.size(); ++k) {
      char line[96];
      std::snprintf(line, sizeof line, "v%zu  %.12g  block %d  %s", k, pairs[k].value.real(), pairs[k].alpha,
                    fourierModeName(pairs[k].mode));
      spectrum.lines.push_back(line);
    }
  } catch (const std::exception& e) {
    spectrum.lines.push_back(e.what());
  }
  spectrum.linesValence = spectrum.valence;
  spectrum.k = std::clamp(spectrum.k, 0, std::max(int(spectrum.lines.size()) - 1, 0));
}

void ViewerApp::updatePoleInspector() {
  PoleInspectorSettings& inspector = state_.poleInspector;
  const bool open = inspector.open;
  inspector.open = false;  // the panel marks it again next frame while the section is open
  if (!model_.mesh) return;
  if (inspectPolesOf_ != model_.generation) {
    inspectPolesOf_ = model_.generation;
    try {
      inspector.poles = modelPoles(*model_.mesh);
    } catch (const std::exception&) {
      inspector.poles.clear();
    }
    inspector.inspections.clear();
    inspectShown_.clear();
  }
  // A finished job: shown if it is still what the panel asks for.
  if (inspectJob_.valid() && inspectJob_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      std::vector<PoleInspection> done = inspectJob_.get();
      inspector.inspections = std::move(done);
      inspector.error.clear();
    } catch (const std::exception& e) {
      inspector.inspections.clear();
      inspector.error = e.what();
    }
    inspectShown_ = inspectRunning_;
  }
  inspector.computing = inspectJob_.valid();
  if (!open || inspector.poles.empty() || inspectJob_.valid()) return;
  // The selected pole under each scheme the visible views show (once each, in view order).
  inspector.pole = std::clamp(inspector.pole, 0, int(inspector.poles.size()) - 1);
  std::vector<SchemeChoice> schemes;
  for (int v = 0; v < state_.viewCount; ++v)
    if (std::find(schemes.begin(), schemes.end(), state_.views[size_t(v)].scheme) == schemes.end())
      schemes.push_back(state_.views[size_t(v)].scheme);
  const Index pole = inspector.poles[size_t(inspector.pole)];
  std::string key = std::to_string(model_.generation) + ":" + std::to_string(model_.points) + ":" + std::to_string(pole);
  for (SchemeChoice scheme : schemes) key += ":" + std::string(schemeChoiceCliName(scheme));
  if (key == inspectShown_) return;
  inspectRunning_ = key;
  inspector.computing = true;
  inspectJob_ = std::async(std::launch::async, [mesh = model_.mesh, pole, schemes] {
    std::vector<PoleInspection> out;
    // Rings deep enough to see the trend: C2PS to ring 10 (valence x 1024), RTS and BPS to 14
    // (they keep n columns), Catmull-Clark to level 8.
    for (SchemeChoice scheme : schemes) {
      const Scheme refined = refineOptionsFor(scheme, 0).scheme;
      const int rings = refined == Scheme::CatmullClark ? 8 : schemeTraits(refined).keepsValence ? 14 : 10;
      out.push_back(inspectPole(*mesh, pole, scheme, rings));
    }
    return out;
  });
}

void ViewerApp::prepareNextLevel(int v, const SurfaceKey& wanted) {
  ViewRuntime& view = views_[size_t(v)];
  if (view.prepare.valid()) {
    if (view.prepare.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    if (!view.prepare.get()) view.prepareFailed = view.preparing;
    // Room on the GPU for the level made ahead, now while idle rather than during the step.
    if (view.shown && view.shown->hierarchy && view.shown->hierarchy->preparedLevel.load() > view.shown->patchLevel)
      view.renderer->reserveFor(view.shown->hierarchy->preparedRegular.load(), view.shown->hierarchy->preparedCaps.load());
  }
  // Only the active view (the one the level keys step) is made ahead: memory for one surface more.
  if (!options_.prepareNextLevel || v >= state_.viewCount || v != std::clamp(state_.activeView, 0, state_.viewCount - 1) ||
      view.job.running() || editor_.dragging() || !view.shown || !view.shown->hierarchy || view.shown->key != wanted)
    return;
  if (wanted.level + 1 > state_.status[size_t(v)].deepestLevel) return;
  const int next = patchLevelFor(model_, wanted.scheme, wanted.level + 1, options_.faceBudget);
  if (view.shown->hierarchy->aheadLevel.load() == wanted.level + 1) return;  // made already
  if (view.previousLevel && view.previousLevel->key.level == wanted.level + 1) return;  // kept from before
  // All views' levels and the one made ahead within one view's budget (memory stays bounded).
  size_t faces = levelFaces(wanted.scheme, next) + parkedFaces();
  for (int w = 0; w < state_.viewCount; ++w)
    faces += levelFaces(state_.views[size_t(w)].scheme,
                                 patchLevelFor(model_, state_.views[size_t(w)].scheme, state_.views[size_t(w)].level,
                                               options_.faceBudget));
  if (faces > options_.faceBudget) return;
  SurfaceKey key = wanted;
  key.level = wanted.level + 1;
  if (view.prepareFailed && *view.prepareFailed == key) return;
  // One view's surface ahead at a time: the other views' and the parked ones' go (the active view
  // follows the mouse).
  std::vector<std::shared_ptr<SurfaceHierarchy>> others;
  for (int w = 0; w < int(views_.size()); ++w)
    for (const auto* surface : {views_[size_t(w)].shown.get(), views_[size_t(w)].parked.get()})
      if (surface && surface->hierarchy && surface->hierarchy != view.shown->hierarchy &&
          surface->hierarchy->aheadLevel.load() >= 0)
        others.push_back(surface->hierarchy);
  view.preparing = key;
  view.prepare = std::async(std::launch::async, [hierarchy = view.shown->hierarchy, others = std::move(others), model = model_, key,
                                                 budget = options_.faceBudget] {
    for (const auto& other : others) dropAhead(*other);
    return prepareLevel(*hierarchy, model, key, budget);
  });
}

bool ViewerApp::busy() const {
  if (loadJob_.valid() || exportJob_.valid()) return true;
  for (int v = 0; v < state_.viewCount; ++v) {
    const ViewRuntime& view = views_[size_t(v)];
    if (view.job.running()) return true;
    if (view.prepare.valid() && view.prepare.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return true;
    SurfaceKey wanted = wantedKey(v);
    if (model_.mesh && (!view.shown || view.shown->key != wanted) && !(view.failed && *view.failed == wanted)) return true;
    // Curvature samples still to be retaken after a drag.
    if (view.shown && view.shown->samples && view.shown->samples->points != model_.points && !editor_.dragging() &&
        !(view.refreshFailed && *view.refreshFailed == wanted))
      return true;
  }
  return false;
}

void ViewerApp::waitUntilIdle() {
  while (busy()) {
    if (loadJob_.valid() || exportJob_.valid()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    pollLoad();
    pollExport();
    for (ViewRuntime& view : views_) {
      if (view.job.running() || view.prepare.valid()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    updateSurfaces();
  }
  updateColourRange();
}

// [SECTION] Editing the control mesh

ViewTransform ViewerApp::viewTransform(int v, const ScreenRect& rect) const {
  // The matrices drawViews gives the renderer (near and far from the model's box).
  const glm::dvec3 centre = 0.5 * (modelMin_ + modelMax_);
  const double radius = 0.5 * glm::length(modelMax_ - modelMin_);
  const OrbitCamera& camera = state_.camera(v);
  ViewTransform transform;
  transform.rect = rect;
  // The view matrix in double (OrbitCamera::viewMatrix's lookAt before its cast to float), so a
  // close-up far from the origin still picks and drags to the pixel.
  transform.viewProjection =
      glm::dmat4(camera.projectionMatrix(double(rect.w) / std::max(double(rect.h), 1.0), centre, radius)) *
      glm::lookAt(camera.eye(), camera.target, camera.up());
  return transform;
}

ViewTransform ViewerApp::viewTransform(int v) const {
  const std::vector<ScreenRect> rects = layoutViews(state_.viewCount, viewArea(), colourBarReserve(state_, 1.0f));
  return viewTransform(v, rects[size_t(std::clamp(v, 0, int(rects.size()) - 1))]);
}

bool ViewerApp::beginVertexDrag(int v, const ScreenRect& rect, float x, float y) {
  if (!model_.mesh) return false;
  const ViewTransform transform = viewTransform(v, rect);
  const int vertex = pickVertex(editor_.points(), transform, x, y);
  if (vertex < 0) return false;
  return editor_.beginDrag(vertex, transform, state_.camera(v).forward(), x, y);
}

void ViewerApp::applyVertexDrag(const VertexDragEvent& drag, const std::vector<ScreenRect>& rects) {
  if (drag.view >= 0 && drag.view < int(rects.size()) &&
      editor_.dragTo(viewTransform(drag.view, rects[size_t(drag.view)]), drag.x, drag.y))
    commitEditedPoints();
  if (drag.released) editor_.endDrag();  // one undo step; the samples are retaken next
}

void ViewerApp::commitEditedPoints() {
  if (!model_.mesh || editor_.points().size() != model_.mesh->points.size()) return;
  // A new mesh object (a background job may still read the old one), the same faces.
  auto mesh = std::make_shared<PolyMesh>(*model_.mesh);
  mesh->points = editor_.points();
  modelMin_ = modelMax_ = mesh->points.front();
  for (const Point& p : mesh->points) {
    modelMin_ = glm::min(modelMin_, p);
    modelMax_ = glm::max(modelMax_, p);
  }
  model_.mesh = std::move(mesh);
  ++model_.points;
  movedVertices_ = editor_.movedVertexCount();
}

void ViewerApp::undoEdit() {
  const std::string what = editor_.undoLabel();
  if (!editor_.undo()) {
    state_.notice = "nothing to undo";
    return;
  }
  commitEditedPoints();
  state_.notice = "undone: " + what;
}

void ViewerApp::redoEdit() {
  const std::string what = editor_.redoLabel();
  if (!editor_.redo()) {
    state_.notice = "nothing to redo";
    return;
  }
  commitEditedPoints();
  state_.notice = "redone: " + what;
}

void ViewerApp::resetEdits() {
  if (!editor_.resetToLoaded()) {
    state_.notice = "no control vertex has moved";
    return;
  }
  commitEditedPoints();
  state_.notice = "every control vertex is back where the file had it (Ctrl+Z undoes the reset)";
}

void ViewerApp::saveEditedMesh() {
  if (!model_.mesh) return;
  const std::string path = state_.edit.savePath.empty() ? state_.edit.defaultSavePath : state_.edit.savePath;
  try {
    saveObj(path, *model_.mesh, model_.name);  // atomic: a failure leaves no file
  } catch (const std::exception& e) {
    state_.edit.error = oneLine(std::string("could not save: ") + e.what());
    state_.notice = state_.edit.error;
    return;
  }
  state_.edit.error.clear();
  state_.notice = "saved the edited mesh to " + absolutePath(path) + " (" + std::to_string(movedVertices_) +
                  (movedVertices_ == 1 ? " vertex" : " vertices") + " moved)";
}

void ViewerApp::startExport(bool bezierView) {
  if (!model_.mesh) return;
  if (exportJob_.valid()) {
    state_.notice = "still writing " + exportTarget_;
    return;
  }
  // What the active view shows: its scheme and level, on the model's current points.
  const int v = std::clamp(state_.activeView, 0, state_.viewCount - 1);
  const BuiltSurface* shown = views_[size_t(v)].shown.get();
  if (!shown || shown->key.model != model_.generation) {
    state_.edit.error = "view " + std::to_string(v + 1) + " shows no surface of this model yet";
    state_.notice = state_.edit.error;
    return;
  }
  const SchemeChoice scheme = shown->key.scheme;
  const int level = shown->key.level;
  const RefineOptions options = refineOptionsFor(scheme, level);
  const Model model = model_;  // the mesh is immutable: the worker keeps this version
  std::string path;
  if (bezierView) {
    path = state_.edit.bvPath.empty() ? state_.edit.defaultBvPath : state_.edit.bvPath;
    // The view's own refinement path and limit (the shown level is within it).
    const size_t maxFaces = 2 * options_.faceBudget;
    exportJob_ = std::async(std::launch::async, [model, options, path, maxFaces, scheme, level] {
      const PatchSet set = cli::exportPatchSet(*model.mesh, options, model.name, false, maxFaces);
      const BezierViewStats stats = cli::writeBezierViewFile(path, set, model.name);
      return "wrote " + absolutePath(path) + ": " + std::to_string(stats.total()) + " Bezier patches (" +
             schemeChoiceLabel(scheme) + " level " + std::to_string(level) + ", feature-adaptive)";
    });
  } else {
    path = state_.edit.refinedObjPath.empty() ? state_.edit.defaultRefinedObjPath : state_.edit.refinedObjPath;
    // Uniform refinement: every face x4 a level (x2 where RTS/BPS refine radially); refused at once
    // when its estimate exceeds what a view may take.
    const size_t budget = options_.faceBudget * kBytesPerAdaptiveFace / kBytesPerUniformFace;
    const bool radial = model.radialForRtsBps && (options.scheme == Scheme::RTS || options.scheme == Scheme::BPS);
    auto facesAt = [&](int l) {
      RefineOptions o = options;
      o.levels = l;
      return estimateFaceCount(*model.mesh, o, radial);
    };
    if (facesAt(level) > budget) {
      int fits = level;
      while (fits > 0 && facesAt(fits) > budget) --fits;
      state_.edit.error = std::string("refined control mesh refused: ") + schemeChoiceLabel(scheme) + " level " +
                          std::to_string(level) + " would have about " + std::to_string(facesAt(level)) +
                          " faces, over the budget of " + std::to_string(budget) + " (level " + std::to_string(fits) +
                          " fits)";
      state_.notice = state_.edit.error;
      return;
    }
    exportJob_ = std::async(std::launch::async, [model, options, path, budget, scheme, level] {
      std::string done;
      {
        RefineOptions written = options;
        written.finestVertexRings = false;  // only its faces and points are written
        const Refinement refinement(*model.mesh, written, model.name, budget);
        // A non-manifold model was refined split: its copies merge back, as `refine` writes it.
        const PolyMesh refined = refinement.splitInput() ? refinement.outputMesh() : refinement.finest().mesh;
        saveObj(path, refined, model.name);
        done = "wrote " + absolutePath(path) + ": the " + schemeChoiceLabel(scheme) + " level " + std::to_string(level) +
               " control mesh (" + std::to_string(refined.faceCount()) + " faces, " +
               std::to_string(refined.vertexCount()) + " vertices)";
      }
      // The refinement's tables went to the pool (up to half the RAM): a viewer keeps none idle.
      clearTablePool();
      return done;
    });
  }
  exportTarget_ = path;
  state_.notice = "writing " + path + "...";
}

void ViewerApp::pollExport() {
  if (!exportJob_.valid() || exportJob_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  try {
    state_.notice = exportJob_.get();
    state_.edit.error.clear();
  } catch (const std::exception& e) {
    // Bad levels, a full disk, an unwritable folder: the atomic writers left nothing behind.
    state_.edit.error = oneLine(std::string("could not write ") + exportTarget_ + ": " + e.what());
    state_.notice = state_.edit.error;
  }
  exportTarget_.clear();
}

void ViewerApp::updateEditState() {
  EditSettings& edit = state_.edit;
  edit.selectedVertex = editor_.selected();
  if (edit.selectedVertex >= 0) edit.selectedPosition = editor_.points()[size_t(edit.selectedVertex)];
  edit.dragging = editor_.dragging();
  edit.undoSteps = int(editor_.undoCount());
  edit.redoSteps = int(editor_.redoCount());
  edit.undoLabel = editor_.undoLabel();
  edit.redoLabel = editor_.redoLabel();
  edit.movedVertices = movedVertices_;
  edit.exporting = exportJob_.valid() ? exportTarget_ : std::string();

  // Default outputs: beside the model file, or in the current directory for the built-in model.
  namespace fs = std::filesystem;
  const std::string& loaded = state_.file.loadedPath;
  const bool builtIn = loaded.empty() || loaded == defaultModelAsset();
  const fs::path folder = builtIn ? fs::path() : fs::path(loaded).parent_path();
  const std::string stem = builtIn ? (state_.file.modelName.rfind("default", 0) == 0 ? "default" : "model")
                                   : fs::path(loaded).stem().string();
  edit.defaultSavePath = (folder / (stem + "_edited.obj")).string();
  // The exports write what the active view shows (its settings until it shows something).
  const int v = std::clamp(state_.activeView, 0, state_.viewCount - 1);
  const BuiltSurface* shown = views_[size_t(v)].shown.get();
  const SchemeChoice scheme = shown ? shown->key.scheme : state_.views[size_t(v)].scheme;
  const int level = shown ? shown->key.level : state_.views[size_t(v)].level;
  const std::string tag = std::string("_") + schemeChoiceCliName(scheme) + "_" + std::to_string(level);
  edit.defaultBvPath = (folder / (stem + tag + ".bv")).string();
  edit.defaultRefinedObjPath = (folder / (stem + tag + "_refined.obj")).string();
}

std::vector<VertexMarker> ViewerApp::vertexMarkers(const std::vector<ScreenRect>& rects) const {
  std::vector<VertexMarker> markers;
  if (!state_.display.controlNet || !model_.mesh) return markers;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (size_t v = 0; v < rects.size(); ++v) {
    if (!views_[v].shown) continue;
    const ViewTransform transform = viewTransform(int(v), rects[v]);
    auto mark = [&](int vertex, bool selected) {
      if (vertex < 0 || size_t(vertex) >= editor_.points().size()) return;
      const std::optional<glm::dvec3> at = transform.project(editor_.points()[size_t(vertex)]);
      if (at && rects[v].contains(float(at->x), float(at->y))) markers.push_back({float(at->x), float(at->y), selected});
    };
    mark(editor_.selected(), true);
    if (rects[v].contains(mouse.x, mouse.y)) mark(state_.edit.hoveredVertex, false);
  }
  return markers;
}

// [SECTION] Drawing

std::vector<PoleMarker> ViewerApp::drawViews(const std::vector<ScreenRect>& rects, float pixelScale,
                                             int framebufferHeight) {
  glm::dvec3 centre = 0.5 * (modelMin_ + modelMax_);
  double radius = 0.5 * glm::length(modelMax_ - modelMin_);
  ShadingParams shading = state_.shading;
  shading.range = state_.colourRange();
  shading.rangeBelow = state_.colourRangeBelow();
  std::vector<PoleMarker> markers;
  for (size_t v = 0; v < rects.size(); ++v) {
    if (!views_[v].shown) continue;
    // Each view in its own style where it has one (render --shade a,b; figures), else the shared one.
    shading.mode = state_.viewShade(int(v));
    // A pole zoom by s = 2^m scales K by 1 / s^2 and H by 1 / s: the range alike, so colours keep values.
    shading.range = state_.colourRange();
    shading.rangeBelow = state_.colourRangeBelow();
    if (views_[v].zoomShown >= 0) {
      const float s = std::ldexp(1.0f, views_[v].zoomShown);
      const float scale = shading.mode == ShadingParams::Mode::Gaussian ? 1.0f / (s * s) : 1.0f / s;
      shading.range *= scale;
      shading.rangeBelow *= scale;
    }
    // Poles are marked by rings in the overlay, not by the renderer's filled discs (which read
    // like a curvature feature right at the pole).
    DisplayFlags display = state_.viewDisplay(int(v));
    const bool markPoles = display.poleMarkers;
    display.poleMarkers = false;
    const ScreenRect& r = rects[v];
    const OrbitCamera& camera = state_.camera(int(v));
    updateDrawnLevel(int(v), double(r.h) * pixelScale);
    ViewParams params;
    params.viewport = glm::ivec4(int(r.x * pixelScale), framebufferHeight - int((r.y + r.h) * pixelScale),
                                 int(r.w * pixelScale), int(r.h * pixelScale));
    params.view = camera.viewMatrix();
    params.proj = camera.projectionMatrix(double(r.w) / std::max(double(r.h), 1.0), centre, radius);
    params.eye = camera.eye();  // double: the renderer draws relative to the eye
    views_[v].renderer->draw(params, shading, display);
    if (markPoles) {
      visiblePoles(views_[v].shown->poles, params, camera.eye(), 0.02 * radius, pixelScale, framebufferHeight, &markers);
    }
  }
  return markers;
}

void ViewerApp::resolvePivot(const PivotPick& pick, const std::vector<ScreenRect>& rects, float pixelScale,
                             int framebufferHeight) {
  // Depth under the cursor (default framebuffer, right after the views were drawn).
  int x = int(pick.x * pixelScale), y = framebufferHeight - 1 - int(pick.y * pixelScale);
  const float depth = readDepthAt(x, y);
  if (depth >= 1.0f) {
    if (pick.zoomNotches != 0.0f) zoomTowardsCursor(state_, rects[size_t(pick.view)], pick.view, pick.zoomNotches);
    else state_.notice = "no surface under the cursor";
    return;
  }
  const ScreenRect& r = rects[size_t(pick.view)];
  OrbitCamera& camera = state_.camera(pick.view);
  glm::dvec3 centre = 0.5 * (modelMin_ + modelMax_);
  double radius = 0.5 * glm::length(modelMax_ - modelMin_);
  const glm::dvec4 viewport(r.x * pixelScale, float(framebufferHeight) - (r.y + r.h) * pixelScale, r.w * pixelScale,
                           r.h * pixelScale);
  const glm::dvec3 world =
      worldOf({x + 0.5, y + 0.5, depth}, camera.eye(), rotationOf(camera.viewMatrix()),
              glm::dmat4(camera.projectionMatrix(double(r.w) / std::max(double(r.h), 1.0), centre, radius)), viewport);
  if (pick.zoomNotches != 0.0f) {
    camera.zoomTowards(glm::dvec3(world), pick.zoomNotches);
    return;
  }
  if (pick.readout && views_[size_t(pick.view)].shown) {
    // The depth buffer holds the surface up to its resolution: search within 1% of the distance.
    const double tolerance = 1e-2 * glm::length(world - camera.eye());
    if (const auto readout = readSurfacePoint(views_[size_t(pick.view)].shown->patches, world, tolerance)) {
      state_.readout = ReadoutSettings{true, pick.view, *readout, readout->text()};
      state_.notice = "K " + std::to_string(readout->point.gaussian) + ", H " + std::to_string(readout->point.mean) +
                      " (panel Point; Copy)";
    }
  }
  if (!pick.movePivot) return;
  camera.setPivotKeepingEye(glm::dvec3(world));
  if (!pick.readout) state_.notice = "pivot set";
}

void ViewerApp::runFrame() {
  auto frameStart = std::chrono::steady_clock::now();
  glfwPollEvents();
  replayInputEvents();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (pointerOverride_) {  // in place of what the backend just read from the system mouse
    ImGuiIO& pointerIo = ImGui::GetIO();
    pointerIo.MousePos = ImVec2(pointerOverride_->x, pointerOverride_->y);
    pointerIo.MouseDown[0] = pointerOverride_->left;
    pointerIo.MouseDown[1] = pointerOverride_->right;
    pointerIo.MouseDown[2] = pointerOverride_->middle;
  }
  // A press or release this frame happens where the cursor was then, not where the backend just
  // found it (it may have moved on within the frame); the next frame sees the rest of the motion.
  if (buttonPosition_) ImGui::GetIO().MousePos = ImVec2(buttonPosition_->first, buttonPosition_->second);
  buttonPosition_.reset();
  ImGui::NewFrame();

  // Panels and input edit the state; requests and dirty views are handled right after.
  ImGuiIO& io = ImGui::GetIO();
  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
  float pixelScale = io.DisplaySize.x > 0 ? float(fbWidth) / io.DisplaySize.x : 1.0f;
  ScreenRect frame = viewArea();
  std::vector<ScreenRect> rects = layoutViews(state_.viewCount, frame, colourBarReserve(state_, 1.0f));
  const InputResult input = input_.handle(state_, rects, [this, &rects](int v, float x, float y) {
    return beginVertexDrag(v, rects[size_t(v)], x, y);
  });
  if (input.vertexDrag) applyVertexDrag(*input.vertexDrag, rects);
  if (input.deselect) editor_.select(-1);
  // The vertex a click would pick: ringed while the net is shown and nothing is dragged.
  state_.edit.hoveredVertex = -1;
  if (state_.display.controlNet && !editor_.dragging() && input.hoveredView >= 0 && model_.mesh) {
    state_.edit.hoveredVertex = pickVertex(editor_.points(), viewTransform(input.hoveredView, rects[size_t(input.hoveredView)]),
                                           io.MousePos.x, io.MousePos.y);
  }
  std::optional<PivotPick> pick = input.pivot;
  if (!pick && pendingPivot_) pick = pendingPivot_;
  pendingPivot_.reset();
  drawViewerPanels(state_);
  frame = viewArea();
  rects = layoutViews(state_.viewCount, frame, colourBarReserve(state_, 1.0f));
  // More or fewer views, or the panels shown or hidden, change every view's shape: re-frame.
  // (a resized window too: its views change shape)
  const ScreenRect area = viewArea();
  if (framedOnce_ && (state_.viewCount != framedViewCount_ || state_.showPanels != framedWithPanels_ ||
                      std::pair{area.w, area.h} != framedAreaSize_))
    frameModel();
  processRequests();
  expireNotice();
  pollLoad();
  pollExport();
  updateSurfaces();
  updatePoleInspector();
  updateSpectrum();
  updateColourRange();
  updateEditState();

  // Draw the views, then the overlay and the UI over them.
  clearFramebuffer(fbWidth, fbHeight, kBackground);
  std::vector<PoleMarker> poles;
  if (fbWidth > 0 && fbHeight > 0) {
    poles = drawViews(rects, pixelScale, fbHeight);
    if (pick) resolvePivot(*pick, rects, pixelScale, fbHeight);
  }
  drawViewOverlay(ImGui::GetBackgroundDrawList(), ImGui::GetFont(), state_, rects, frame, 1.0f, poles,
                  vertexMarkers(rects));
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  finishGpuWork();  // frame time includes the GPU work (not the swap's wait for vsync)
  state_.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
  if (!windowCapturePath_.empty()) {
    try {
      writePngAtomic(windowCapturePath_, readFramebuffer(0, 0, fbWidth, fbHeight));
      std::printf("%s\n", windowCapturePath_.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "polarview: %s\n", e.what());
    }
    windowCapturePath_.clear();
  }
  glfwSwapBuffers(window_);
  ++framesDrawn_;
}

void ViewerApp::expireNotice() {
  const auto now = std::chrono::steady_clock::now();
  if (state_.notice != shownNotice_) {
    shownNotice_ = state_.notice;
    noticeSince_ = now;
  } else if (!state_.notice.empty() && now - noticeSince_ > kNoticeLifetime) {
    state_.notice.clear();
    shownNotice_.clear();
  }
}

bool ViewerApp::shouldClose() const { return glfwWindowShouldClose(window_); }

// [SECTION] Offscreen images and screenshots

RgbaImage ViewerApp::renderImage(int width, int height, int supersample, bool transparent) {
  if (framesDrawn_ == 0) runFrame();  // builds the ImGui font texture and draw-list data
  OffscreenTarget target;
  std::string error;
  if (!target.create(width, height, supersample, &error)) throw std::runtime_error("offscreen target: " + error);
  target.bindAndClear(kBackground[0], kBackground[1], kBackground[2], transparent ? 0.0f : 1.0f);

  // Same layout as on screen, in render pixels, without the panels.
  const float scale = float(target.supersample());
  ScreenRect frame{0, 0, float(target.renderWidth()), float(target.renderHeight())};
  std::vector<ScreenRect> rects = layoutViews(state_.viewCount, frame, colourBarReserve(state_, scale));
  std::vector<PoleMarker> poles = drawViews(rects, 1.0f, target.renderHeight());

  // Labels and colour bar: a private ImGui draw list rendered by the OpenGL3 backend.
  ImDrawList list(ImGui::GetDrawListSharedData());
  list._ResetForNewFrame();
  list.PushTextureID(ImGui::GetIO().Fonts->TexID);
  list.PushClipRect(ImVec2(0, 0), ImVec2(frame.w, frame.h));
  drawViewOverlay(&list, ImGui::GetIO().Fonts->Fonts[0], state_, rects, frame, scale, poles);
  ImDrawList* lists[] = {&list};
  ImDrawData data;
  data.Valid = true;
  data.CmdLists = lists;
  data.CmdListsCount = 1;
  data.TotalVtxCount = list.VtxBuffer.Size;
  data.TotalIdxCount = list.IdxBuffer.Size;
  data.DisplayPos = ImVec2(0, 0);
  data.DisplaySize = ImVec2(frame.w, frame.h);
  data.FramebufferScale = ImVec2(1, 1);
  ImGui_ImplOpenGL3_RenderDrawData(&data);

  RgbaImage image = target.read();
  OffscreenTarget::bindDefault();
  return image;
}

std::string ViewerApp::saveScreenshot() {
  namespace fs = std::filesystem;
  std::string path;
  for (int i = 1; i < 100000; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "polarview_%04d.png", i);
    if (!fs::exists(name)) {
      path = name;
      break;
    }
  }
  try {
    // The views as laid out on screen (the panel column left out), at framebuffer resolution.
    int width = 0, height = 0, windowWidth = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    glfwGetWindowSize(window_, &windowWidth, nullptr);
    const ScreenRect area = viewArea();
    const double pixelScale = windowWidth > 0 ? double(width) / windowWidth : 1.0;
    RgbaImage image = renderImage(std::max(int(std::lround(area.w * pixelScale)), 1),
                                  std::max(int(std::lround(area.h * pixelScale)), 1), state_.screenshot.supersample,
                                  state_.screenshot.transparent);
    writePngAtomic(path, image);
  } catch (const std::exception& e) {
    state_.notice = std::string("screenshot failed: ") + e.what();
    return {};
  }
  std::string absolute = fs::absolute(path).string();
  std::printf("%s\n", absolute.c_str());
  std::fflush(stdout);
  state_.screenshot.lastPath = absolute;
  state_.notice = "wrote " + absolute;
  return absolute;
}

}  // namespace polarview
