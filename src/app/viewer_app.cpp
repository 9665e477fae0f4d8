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
#include <filesystem>
#include <thread>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gl_context.h"
#include "render/patch_renderer.h"
#include "render/shader_library.h"
#include "pipeline/surface_build.h"
#include "session/command_table.h"

namespace polarview {
namespace {

// [SECTION] Constants and helpers

constexpr const char* kFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

}  // namespace

// [SECTION] Set-up and tear-down

ViewerApp::ViewerApp(const ViewerOptions& options)
    : options_(options),
      session_(SessionOptions{options.faceBudget, options.prepareNextLevel, options.persistRecent}, *this),
      settings_(session_.settings()),
      status_(session_.status()) {}

ViewerApp::~ViewerApp() {
  // Jobs finish first (their futures block), then GL objects go while the context still exists.
  if (window_) {
    glfwMakeContextCurrent(window_);
    gpu_.reset();  // GPU buffers go while the context exists
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
    gpu_ = std::make_unique<GpuMirror>(shaders_, GpuMirror::LevelOfDetail{options_.levelOfDetail, options_.levelOfDetailPixels});
  } catch (const std::exception& e) {
    if (error) *error = e.what();
    return false;
  }
  status_.glInfo = currentGlVersion();
  for (const std::string& command : options_.scriptedCommands) {
    std::string refusal;
    if (!viewerCommands().parse(command, &refusal)) {
      if (error) *error = refusal + " (polarview help keys lists the commands)";
      return false;
    }
    session_.queueCommand(command);
  }
  if (options_.persistRecent) document().loadRecent();
  return true;
}

// [SECTION] Models and files

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
  if (app) app->session_.apply(app->document().dropFiles(count, paths));
}

ScreenRect ViewerApp::viewArea() const {
  int width = options_.width, height = options_.height;
  if (window_) glfwGetWindowSize(window_, &width, &height);
  const float panel = std::min(panelColumnWidth(settings_), float(width) * 0.5f);
  return ScreenRect{panel, 0, std::max(float(width) - panel, 1.0f), std::max(float(height), 1.0f)};
}

std::vector<glm::dvec3> ViewerApp::zoomedRingPoints() const {
  // The control points of the zoomed rings (their hull holds the surface) of the first view that
  // has them, as GpuMirror::upload zooms them; empty without a pole zoom.
  const PoleInspectorSettings& inspector = settings_.poleInspector;
  std::vector<glm::dvec3> points;
  if (inspector.zoomRing < 0) return points;
  for (int v = 0; v < settings_.viewCount && points.empty(); ++v) {
    const BuiltSurface* shown = session_.surfaces().shown(v).get();
    if (!shown || shown->poles.empty()) continue;
    const int pole = std::clamp(inspector.pole, 0, int(shown->poles.size()) - 1);
    for (const Patch& patch : zoomAboutPole(shown->patches, pole, inspector.zoomRing, 3, shown->poles[size_t(pole)])) {
      if (patch.kind == PatchKind::PoleCap) points.push_back(patch.origin + patch.cp[0]);  // the pole
      else
        for (const glm::dvec3& p : patch.cp) points.push_back(patch.origin + p);
    }
  }
  return points;
}

void ViewerApp::frameModel(const ScreenRect* viewRect) {
  const ScreenRect view =
      viewRect ? *viewRect : layoutViews(settings_.viewCount, viewArea(), colourBarReserve(settings_, 1.0f)).front();
  const double aspect = double(view.w) / std::max(double(view.h), 1.0);
  // Keep the model out from under the view's title (a strip at the top; symmetric, so centred).
  const double heightFraction = std::max(0.5, 1.0 - 2.0 * double(viewTitleHeight(1.0f)) / std::max(double(view.h), 1.0));
  // A pole zoom shows rings m..m+2 scaled about the pole: those are what F frames.
  const std::vector<glm::dvec3> zoomed = zoomedRingPoints();
  auto frameCamera = [&](OrbitCamera& camera) {
    if (!zoomed.empty()) camera.framePoints(zoomed.data(), zoomed.size(), aspect, heightFraction);
    else if (model().mesh) camera.framePoints(model().mesh->points.data(), model().mesh->points.size(), aspect, heightFraction);
    else camera.frame(document().modelMin(), document().modelMax(), aspect);
  };
  if (settings_.linkCameras) {
    frameCamera(settings_.sharedCamera);
  } else {
    for (View& view : settings_.views) frameCamera(view.camera);
  }
  framedOnce_ = true;
  framedViewCount_ = settings_.viewCount;
  framedWithPanels_ = settings_.showPanels;
  const ScreenRect area = viewArea();
  framedAreaSize_ = {area.w, area.h};
}

// [SECTION] Commands (session/command_table.h): what they ask of the application

void ViewerApp::setClipboard(const std::string& text) { glfwSetClipboardString(window_, text.c_str()); }

std::string ViewerApp::clipboard() {
  const char* text = glfwGetClipboardString(window_);
  return text ? text : "";
}

// [SECTION] Rebuilding what is dirty

void ViewerApp::updateSurfaces() {
  std::optional<EditCost> cost = session_.updateModelAndSurfaces();
  // A view not drawn yet uploads for its height in the window (GpuMirror::sync).
  const std::vector<ScreenRect> rects = layoutViews(settings_.viewCount, viewArea(), colourBarReserve(settings_, 1.0f));
  for (int v = 0; v < kMaxViews; ++v) {
    const double firstHigh = v < int(rects.size()) ? double(rects[size_t(v)].h) : 0.0;
    const double uploadMs = gpu_->sync(v, session_.surfaces(), settings_, status_, document().model(), firstHigh);
    if (cost && session_.surfaces().refreshed(v)) {  // the upload is part of an edit's cost
      cost->uploadMs += uploadMs;
      cost->totalMs += uploadMs;
    }
    gpu_->report(v, status_.views[size_t(v)]);
  }
  if (cost) document().recordEditCost(*cost);
}

void ViewerApp::waitUntilIdle() {
  while (busy()) {
    if (document().loading() || document().exporting()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    session_.surfaces().pause();
    updateSurfaces();
  }
  session_.updateColourRange();
}

// [SECTION] Editing the control mesh

ViewTransform ViewerApp::viewTransform(int v, const ScreenRect& rect) const {
  // The matrices drawViews gives the renderer (near and far from the model's box).
  const glm::dvec3 centre = 0.5 * (document().modelMin() + document().modelMax());
  const double radius = 0.5 * glm::length(document().modelMax() - document().modelMin());
  const OrbitCamera& camera = settings_.camera(v);
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
  const std::vector<ScreenRect> rects = layoutViews(settings_.viewCount, viewArea(), colourBarReserve(settings_, 1.0f));
  return viewTransform(v, rects[size_t(std::clamp(v, 0, int(rects.size()) - 1))]);
}

bool ViewerApp::beginVertexDrag(int v, const ScreenRect& rect, float x, float y) {
  if (!model().mesh) return false;
  const ViewTransform transform = viewTransform(v, rect);
  const int vertex = pickVertex(document().editor().points(), transform, x, y);
  if (vertex < 0) return false;
  return document().editor().beginDrag(vertex, transform, settings_.camera(v).forward(), x, y);
}

void ViewerApp::applyVertexDrag(const VertexDragEvent& drag, const std::vector<ScreenRect>& rects) {
  if (drag.view >= 0 && drag.view < int(rects.size()) &&
      document().editor().dragTo(viewTransform(drag.view, rects[size_t(drag.view)]), drag.x, drag.y))
    document().commitEditedPoints();
  if (drag.released) document().editor().endDrag();  // one undo step; the samples are retaken next
}

std::vector<VertexMarker> ViewerApp::vertexMarkers(const std::vector<ScreenRect>& rects) const {
  std::vector<VertexMarker> markers;
  if (!settings_.display.controlNet || !model().mesh) return markers;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  for (size_t v = 0; v < rects.size(); ++v) {
    if (!session_.surfaces().shown(int(v))) continue;
    const ViewTransform transform = viewTransform(int(v), rects[v]);
    auto mark = [&](int vertex, bool selected) {
      if (vertex < 0 || size_t(vertex) >= document().editor().points().size()) return;
      const std::optional<glm::dvec3> at = transform.project(document().editor().points()[size_t(vertex)]);
      if (at && rects[v].contains(float(at->x), float(at->y))) markers.push_back({float(at->x), float(at->y), selected});
    };
    mark(document().editor().selected(), true);
    if (rects[v].contains(mouse.x, mouse.y)) mark(status_.edit.hoveredVertex, false);
  }
  return markers;
}

std::vector<PointMarker> ViewerApp::pointMarkers(const std::vector<ScreenRect>& rects) const {
  // The Point panel's surface point where its view shows it now (the camera may have moved since).
  const ReadoutStatus& readout = status_.readout;
  if (!readout.valid || readout.view >= int(rects.size()) || settings_.poleInspector.zoomRing >= 0) return {};
  const ScreenRect& rect = rects[size_t(readout.view)];
  const std::optional<glm::dvec3> at = viewTransform(readout.view, rect).project(readout.readout.point.position);
  if (!at || !rect.contains(float(at->x), float(at->y))) return {};
  return {PointMarker{float(at->x), float(at->y)}};
}

// [SECTION] Drawing

void ViewerApp::resolvePivot(const PivotPick& pick, const std::vector<ScreenRect>& rects, float pixelScale,
                             int framebufferHeight) {
  // Depth under the cursor (default framebuffer, right after the views were drawn).
  int x = int(pick.x * pixelScale), y = framebufferHeight - 1 - int(pick.y * pixelScale);
  const float depth = readDepthAt(x, y);
  if (depth >= 1.0f) {
    if (pick.zoomNotches != 0.0f) zoomTowardsCursor(settings_, rects[size_t(pick.view)], pick.view, pick.zoomNotches);
    else session_.notices().post(info("no surface under the cursor"));
    return;
  }
  const ScreenRect& r = rects[size_t(pick.view)];
  OrbitCamera& camera = settings_.camera(pick.view);
  glm::dvec3 centre = 0.5 * (document().modelMin() + document().modelMax());
  double radius = 0.5 * glm::length(document().modelMax() - document().modelMin());
  const glm::dvec4 viewport(r.x * pixelScale, float(framebufferHeight) - (r.y + r.h) * pixelScale, r.w * pixelScale,
                           r.h * pixelScale);
  const glm::dvec3 world =
      worldOf({x + 0.5, y + 0.5, depth}, camera.eye(), rotationOf(camera.viewMatrix()),
              glm::dmat4(camera.projectionMatrix(double(r.w) / std::max(double(r.h), 1.0), centre, radius)), viewport);
  if (pick.zoomNotches != 0.0f) {
    camera.zoomTowards(glm::dvec3(world), pick.zoomNotches);
    return;
  }
  if (pick.readout && session_.surfaces().shown(pick.view)) {
    const BuiltSurface& shown = *session_.surfaces().shown(pick.view);
    // The depth buffer holds the surface up to its resolution: search within 1% of the distance.
    double tolerance = 1e-2 * glm::length(world - camera.eye());
    glm::dvec3 onSurface = world;
    // A pole zoom draws the rings scaled by 2^m about the pole (zoomAboutPole): the point picked is
    // that of the surface itself scaled back.
    const int zoom = settings_.poleInspector.zoomRing;
    if (zoom >= 0 && !shown.poles.empty()) {
      const Point& pole = shown.poles[size_t(std::clamp(settings_.poleInspector.pole, 0, int(shown.poles.size()) - 1))];
      onSurface = pole + std::ldexp(1.0, -zoom) * (world - pole);
      tolerance = std::ldexp(tolerance, -zoom);
    }
    if (const auto readout = readSurfacePoint(shown.patches, onSurface, tolerance)) {
      status_.readout = ReadoutStatus{true, pick.view, *readout, readout->text()};
      session_.notices().post(info("K " + std::to_string(readout->point.gaussian) + ", H " + std::to_string(readout->point.mean) +
                                   " (panel Point; Copy)"));
    }
  }
  if (!pick.movePivot) return;
  camera.setPivotKeepingEye(glm::dvec3(world));
  if (!pick.readout) session_.notices().post(info("pivot set"));
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
  std::vector<ScreenRect> rects = layoutViews(settings_.viewCount, frame, colourBarReserve(settings_, 1.0f));
  PanelContext panels{settings_, status_, session_.notices(), session_.commandQueue()};
  const InputResult input = input_.handle(panels, rects, [this, &rects](int v, float x, float y) {
    return beginVertexDrag(v, rects[size_t(v)], x, y);
  });
  if (input.vertexDrag) applyVertexDrag(*input.vertexDrag, rects);
  if (input.deselect) document().editor().select(-1);
  // The vertex a click would pick: ringed while the net is shown and nothing is dragged.
  status_.edit.hoveredVertex = -1;
  if (settings_.display.controlNet && !document().editor().dragging() && input.hoveredView >= 0 && model().mesh) {
    status_.edit.hoveredVertex = pickVertex(document().editor().points(), viewTransform(input.hoveredView, rects[size_t(input.hoveredView)]),
                                           io.MousePos.x, io.MousePos.y);
  }
  std::optional<PivotPick> pick = input.pivot;
  if (!pick && pendingPivot_) pick = pendingPivot_;
  pendingPivot_.reset();
  // This frame's keys and commands reach the surfaces before the panels are drawn, so the Stats
  // panel shows the status the views' titles show (it lagged them by a frame); what a panel
  // changes is taken up next frame.
  viewerCommands().runQueued(session_);
  session_.expireNotice();
  updateSurfaces();
  session_.updatePanels();
  drawViewerPanels(panels);
  frame = viewArea();
  rects = layoutViews(settings_.viewCount, frame, colourBarReserve(settings_, 1.0f));
  // More or fewer views, or the panels shown or hidden, change every view's shape: re-frame.
  // (a resized window too: its views change shape)
  const ScreenRect area = viewArea();
  if (framedOnce_ && (settings_.viewCount != framedViewCount_ || settings_.showPanels != framedWithPanels_ ||
                      std::pair{area.w, area.h} != framedAreaSize_))
    frameModel();

  // Draw the views, then the overlay and the UI over them.
  clearFramebuffer(fbWidth, fbHeight, kBackground);
  std::vector<PoleMarker> poles;
  if (fbWidth > 0 && fbHeight > 0) {
    poles = gpu_->draw(rects, pixelScale, fbHeight, settings_, status_, document());
    if (pick) resolvePivot(*pick, rects, pixelScale, fbHeight);
  }
  lastPoleMarkers_ = poles;
  drawViewOverlay(ImGui::GetBackgroundDrawList(), ImGui::GetFont(), settings_, status_, rects, frame, 1.0f, poles,
                  vertexMarkers(rects), pointMarkers(rects));
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  finishGpuWork();  // frame time includes the GPU work (not the swap's wait for vsync)
  status_.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
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
  std::vector<ScreenRect> rects = layoutViews(settings_.viewCount, frame, colourBarReserve(settings_, scale));
  std::vector<PoleMarker> poles = gpu_->draw(rects, 1.0f, target.renderHeight(), settings_, status_, document());

  // Labels and colour bar: a private ImGui draw list rendered by the OpenGL3 backend.
  ImDrawList list(ImGui::GetDrawListSharedData());
  list._ResetForNewFrame();
  list.PushTextureID(ImGui::GetIO().Fonts->TexID);
  list.PushClipRect(ImVec2(0, 0), ImVec2(frame.w, frame.h));
  drawViewOverlay(&list, ImGui::GetIO().Fonts->Fonts[0], settings_, status_, rects, frame, scale, poles);
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
                                  std::max(int(std::lround(area.h * pixelScale)), 1), settings_.screenshot.supersample,
                                  settings_.screenshot.transparent);
    writePngAtomic(path, image);
  } catch (const std::exception& e) {
    session_.notices().post(error(std::string("screenshot failed: ") + e.what()));
    return {};
  }
  std::string absolute = fs::absolute(path).string();
  std::printf("%s\n", absolute.c_str());
  std::fflush(stdout);
  status_.lastScreenshot = absolute;
  session_.notices().post(info("wrote " + absolute));
  return absolute;
}

}  // namespace polarview
