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

ViewerApp::ViewerApp(const ViewerOptions& options)
    : options_(options), surfaces_(options.faceBudget, options.prepareNextLevel) {}

ViewerApp::~ViewerApp() {
  // Jobs finish first (their futures block), then GL objects go while the context still exists.
  loadJob_.join();
  exportJob_.join();
  inspectJob_.join();
  if (window_) {
    glfwMakeContextCurrent(window_);
    for (GpuView& view : gpu_) view = GpuView{};  // GPU buffers go while the context exists
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
  try {
    for (GpuView& view : gpu_) view.shown.renderer = makeRenderer();
  } catch (const std::exception& e) {
    if (error) *error = e.what();
    return false;
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
  if (loadJob_.running()) {
    queuedLoad_ = path;  // started when the running one is done; its result is then dropped
    return;
  }
  state_.file.loading = true;
  state_.file.loadingPath = path;
  loadJob_.start([path] { return readModelFile(path); });
}

void ViewerApp::pollLoad() {
  std::optional<LoadedModel> done = loadJob_.poll();  // readModelFile never throws
  if (!done) return;
  LoadedModel loaded = std::move(*done);
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
  model_ = Model{std::make_shared<const PolyMesh>(std::move(mesh)), name, model_.generation + 1};
  model_.radialForRtsBps = refinesRadially(*model_.mesh, Scheme::RTS);
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
  surfaces_.modelChanged(state_);
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

// [SECTION] Commands (session/command_table.h): what they ask of the application

void ViewerApp::undo() {
  // Ctrl+Z undoes vertex drags first; with none left it goes back to the previous model.
  if (editor_.undoCount() > 0) undoEdit();
  else undoModelReplacement();
}

void ViewerApp::reloadModel() {
  if (state_.file.loadedPath.empty()) loadDefaultModel();
  else requestLoad(state_.file.loadedPath);
}

void ViewerApp::showEigenvector() {
  const SpectrumSettings& spectrum = state_.spectrum;
  try {
    const std::string name = "RTS eigenvector v" + std::to_string(spectrum.k) + ", valence " + std::to_string(spectrum.valence) +
                             (spectrum.c2psSteps > 0 ? ", " + std::to_string(spectrum.c2psSteps) + " C2PS steps" : "");
    if (loadMesh(eigenNet(spectrum.valence, spectrum.k, spectrum.c2psSteps), name, "")) state_.notice = name + " (Ctrl+Z returns)";
  } catch (const std::exception& e) {
    state_.notice = std::string("eigenvector: ") + e.what();
  }
}

void ViewerApp::convertToPolar(bool pentagons) {
  if (!model_.mesh) return;
  try {
    PolarConversion conversion = convertExtraordinaryToPolar(*model_.mesh, pentagons, model_.name);
    if (conversion.converted.empty()) {
      state_.notice = "no extraordinary vertex to convert (interior, all quads around it, valence != 4)";
      return;
    }
    const size_t count = conversion.converted.size();
    const std::string name = "converted (Fig. 14" + std::string(pentagons ? "c" : "a") + "): " + model_.name;
    if (loadMesh(std::move(conversion.mesh), name, ""))
      state_.notice = std::to_string(count) + " extraordinary vertices made poles (Ctrl+Z returns)";
  } catch (const std::exception& e) {
    state_.notice = std::string("conversion failed: ") + e.what();
  }
}

void ViewerApp::setClipboard(const std::string& text) { glfwSetClipboardString(window_, text.c_str()); }

std::string ViewerApp::clipboard() {
  const char* text = glfwGetClipboardString(window_);
  return text ? text : "";
}

// [SECTION] Rebuilding what is dirty

ViewerApp::UploadCost ViewerApp::upload(int v, const BuiltSurface& surface) {
  GpuSlot& slot = gpu_[size_t(v)].shown;
  // A level step on the same hierarchy keeps the patches both levels share on the GPU.
  const auto start = std::chrono::steady_clock::now();
  const int zoom = surface.poles.empty() ? -1 : state_.poleInspector.zoomRing;
  if (zoom >= 0) {
    // Pole zoom: the rings of the inspected pole, scaled in double (a new upload: no stable prefix).
    const int pole = std::clamp(state_.poleInspector.pole, 0, int(surface.poles.size()) - 1);
    slot.renderer->setPatches(zoomAboutPole(surface.patches, pole, zoom, 3, surface.poles[size_t(pole)]));
  } else {
    slot.renderer->setPatches(surface.patches, surface.stamp, surface.regularCount);
  }
  slot.zoom = zoom;
  return {millisecondsSince(start), slot.renderer->lastReusedPatches()};
}

std::unique_ptr<PatchRenderer> ViewerApp::makeRenderer() const {
  auto renderer = std::make_unique<PatchRenderer>();
  std::string log;
  if (!renderer->init(&log, shaders_)) throw std::runtime_error("shaders: " + log);  // compiled once already
  return renderer;
}

double ViewerApp::syncGpu(int v) {
  GpuView& gpu = gpu_[size_t(v)];
  const std::shared_ptr<const BuiltSurface>& shown = surfaces_.shown(v);
  const std::shared_ptr<const BuiltSurface>& parked = surfaces_.parked(v);
  // Each renderer keeps what it draws: a scheme toggle back swaps them (nothing uploaded).
  const auto swapStart = std::chrono::steady_clock::now();
  const bool swapped = shown && gpu.parked.surface == shown;
  if (swapped) std::swap(gpu.shown, gpu.parked);
  if (gpu.parked.surface != parked) {
    if (parked && gpu.shown.surface == parked) {
      // The shown surface was parked: it keeps its renderer, the new one gets another.
      gpu.parked = std::move(gpu.shown);
      gpu.shown = GpuSlot{};
    } else {
      gpu.parked = GpuSlot{};  // its GPU buffers go
    }
  }
  if (!gpu.shown.renderer) gpu.shown.renderer = makeRenderer();
  if (swapped) {
    gpu.uploadMs = millisecondsSince(swapStart);
    gpu.keptPatches = shown->patches.size();
  }
  const int zoom = !shown || shown->poles.empty() ? -1 : state_.poleInspector.zoomRing;
  if (!shown || (gpu.shown.surface == shown && gpu.shown.zoom == zoom)) return 0.0;
  const UploadCost cost = upload(v, *shown);
  gpu.uploadMs = cost.milliseconds;  // the Stats panel's: a level-of-detail switch does not count
  gpu.keptPatches = surfaces_.refreshed(v) ? 0 : cost.keptPatches;  // moved points: no patch stayed
  gpu.shown.surface = shown;
  gpu.shown.drawn.reset();  // the level of detail is picked again for the new surface
  gpu.shown.renderer->setControlMesh(shown->controlMesh, shown->netSegments);
  gpu.shown.renderer->setPoleMarkers(shown->poles);
  return cost.milliseconds;
}

void ViewerApp::updateDrawnLevel(int v, double pixelsHigh) {
  GpuSlot& slot = gpu_[size_t(v)].shown;
  const BuiltSurface* shown = slot.surface.get();
  if (!shown || slot.zoom >= 0) return;
  // While a drag moves points every frame the full set is drawn (each new set would be assembled anew).
  int wanted = shown->patchLevel;
  if (options_.levelOfDetail && !state_.edit.dragging && shown->key.points == model_.points)
    wanted = levelToDraw(shown->detail, shown->patchLevel, state_.camera(v), pixelsHigh, options_.levelOfDetailPixels);
  const int drawnNow = slot.drawn ? slot.drawn->patchLevel : shown->patchLevel;
  if (wanted != drawnNow) {
    std::shared_ptr<const BuiltSurface> drawn = wanted < shown->patchLevel ? drawnSurface(*shown, model_, wanted) : nullptr;
    if (wanted >= shown->patchLevel || drawn) {  // else not available now (an edit is applied): keep
      upload(v, drawn ? *drawn : *shown);
      slot.drawn = std::move(drawn);
    }
  }
  ViewStatus& status = state_.status[size_t(v)];
  status.drawnLevel = slot.drawn ? slot.drawn->patchLevel : shown->patchLevel;
  status.drawnPatches = int(slot.drawn ? slot.drawn->patches.size() : shown->patches.size());
}

void ViewerApp::updateSurfaces() {
  std::optional<EditCost> cost = surfaces_.update(state_, model_, editor_.dragging());
  for (int v = 0; v < kMaxViews; ++v) {
    if (std::optional<GpuReservation> room = surfaces_.takeReservation(v))
      gpu_[size_t(v)].shown.renderer->reserveFor(room->regularPatches, room->capPatches);
    const double uploadMs = syncGpu(v);
    if (cost && surfaces_.refreshed(v)) {
      cost->uploadMs += uploadMs;
      cost->totalMs += uploadMs;
    }
    ViewStatus& status = state_.status[size_t(v)];
    const GpuView& gpu = gpu_[size_t(v)];
    status.uploadMs = gpu.uploadMs;
    status.keptPatches = int(gpu.keptPatches);
    status.zoomRing = gpu.shown.zoom;
    if (const BuiltSurface* shown = gpu.shown.surface.get()) {
      status.drawnLevel = gpu.shown.drawn ? gpu.shown.drawn->patchLevel : shown->patchLevel;
      status.drawnPatches = int(gpu.shown.drawn ? gpu.shown.drawn->patches.size() : shown->patches.size());
    }
  }
  if (!cost) return;
  if (editCosts_.size() >= kMaxEditCosts) editCosts_.erase(editCosts_.begin());
  editCosts_.push_back(*cost);
  state_.edit.positionsMs = cost->positionsMs;
  state_.edit.patchesMs = cost->patchesMs;
  state_.edit.uploadMs = cost->uploadMs;
  state_.edit.totalMs = cost->totalMs;
  state_.edit.updatedViews = cost->views;
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
    if (surfaces_.shown(v)) hashMix(signature, uint64_t(uintptr_t(surfaces_.shown(v)->samples.get())));
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
    if (!surfaces_.shown(v) || !surfaces_.shown(v)->samples) continue;
    const CurvatureSamples& s = *surfaces_.shown(v)->samples;
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
  if (inspectJob_.finished()) {
    try {
      inspector.inspections = std::move(*inspectJob_.poll());
      inspector.error.clear();
    } catch (const std::exception& e) {
      inspector.inspections.clear();
      inspector.error = e.what();
    }
    inspectShown_ = inspectRunning_;
  }
  inspector.computing = inspectJob_.running();
  if (!open || inspector.poles.empty() || inspectJob_.running()) return;
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
  inspectJob_.start([mesh = model_.mesh, pole, schemes] {
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

bool ViewerApp::busy() const {
  return loadJob_.running() || exportJob_.running() || surfaces_.busy(state_, model_, editor_.dragging());
}

void ViewerApp::waitUntilIdle() {
  while (busy()) {
    if (loadJob_.running() || exportJob_.running()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    pollLoad();
    pollExport();
    surfaces_.pause();
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
  if (exportJob_.running()) {
    state_.notice = "still writing " + exportTarget_;
    return;
  }
  // What the active view shows: its scheme and level, on the model's current points.
  const int v = std::clamp(state_.activeView, 0, state_.viewCount - 1);
  const BuiltSurface* shown = surfaces_.shown(v).get();
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
    exportJob_.start([model, options, path, maxFaces, scheme, level] {
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
    exportJob_.start([model, options, path, budget, scheme, level] {
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
  if (!exportJob_.finished()) return;
  try {
    state_.notice = *exportJob_.poll();
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
  edit.exporting = exportJob_.running() ? exportTarget_ : std::string();

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
  const BuiltSurface* shown = surfaces_.shown(v).get();
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
    if (!surfaces_.shown(int(v))) continue;
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
    const GpuSlot& gpu = gpu_[v].shown;
    if (!gpu.surface) continue;
    // Each view in its own style where it has one (render --shade a,b; figures), else the shared one.
    shading.mode = state_.viewShade(int(v));
    // A pole zoom by s = 2^m scales K by 1 / s^2 and H by 1 / s: the range alike, so colours keep values.
    shading.range = state_.colourRange();
    shading.rangeBelow = state_.colourRangeBelow();
    if (gpu.zoom >= 0) {
      const float s = std::ldexp(1.0f, gpu.zoom);
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
    gpu.renderer->draw(params, shading, display);
    if (markPoles) {
      visiblePoles(gpu.surface->poles, params, camera.eye(), 0.02 * radius, pixelScale, framebufferHeight, &markers);
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
  if (pick.readout && surfaces_.shown(pick.view)) {
    // The depth buffer holds the surface up to its resolution: search within 1% of the distance.
    const double tolerance = 1e-2 * glm::length(world - camera.eye());
    if (const auto readout = readSurfacePoint(surfaces_.shown(pick.view)->patches, world, tolerance)) {
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
  viewerCommands().runQueued(state_, *this);
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
