// The page's program (docs/web.md): the ImGui example order for emscripten (GLFW window with a
// WebGL2 context, ImGui, a main loop the browser drives), over WebScene (what is shown, GL-free)
// and WebRenderer (the one WebGL file). The page (web/index.html) calls pv_load_obj for opened and
// dropped files and shows the messages this program sends it.
#include <GLFW/glfw3.h>
#include <GLES3/gl3.h>
#include <emscripten.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/orbit_camera.h"
#include "pipeline/screen_rect.h"
#include "web_gl.h"
#include "web_query.h"
#include "web_scene.h"

namespace polarview {
namespace {

constexpr float kPanelWidth = 330.0f;
constexpr float kTitleHeight = 34.0f;                   // the desktop's viewTitleHeight
constexpr float kHistogramHeight = 18.0f;               // the desktop's colour bar strip (ui/viewer_panels.cpp)
constexpr float kColourBarStrip = 64.0f + kHistogramHeight + 4.0f;
const ImU32 kOverlayBox = IM_COL32(20, 21, 24, 200);
const ImU32 kOverlayText = IM_COL32(230, 230, 230, 255);

ImU32 toImColour(const glm::vec3& c) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1.0f)); }

std::string formatTick(double value, double scale) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", std::abs(value) <= 1e-9 * scale ? 0.0 : value);
  return buffer;
}

// The desktop's layoutViews (ui/viewer_panels.cpp): a row, or a full grid when clearly larger.
std::vector<ScreenRect> layoutViews(int count, const ScreenRect& frame, float bottomReserve) {
  const float height = std::max(frame.h - bottomReserve, 1.0f);
  int columns = count;
  float best = 0.0f;
  for (int c = count; c >= 1; --c) {
    if (count % c != 0) continue;
    const float side = std::min(frame.w / float(c), height / float(count / c));
    if (side > best * 1.15f) {
      best = side;
      columns = c;
    }
  }
  const int rows = (count + columns - 1) / columns;
  std::vector<ScreenRect> rects(static_cast<size_t>(count));
  for (int v = 0; v < count; ++v) {
    const int column = v % columns, row = v / columns;
    const float left = std::floor(frame.x + frame.w * float(column) / float(columns));
    const float right = std::floor(frame.x + frame.w * float(column + 1) / float(columns));
    const float top = std::floor(frame.y + height * float(row) / float(rows));
    const float bottom = std::floor(frame.y + height * float(row + 1) / float(rows));
    rects[size_t(v)] = {left, top, right - left, bottom - top};
  }
  return rects;
}

void showMessage(const std::string& text) {
  EM_ASM({ if (window.pvShowMessage) window.pvShowMessage(UTF8ToString($0)); }, text.c_str());
}

// What the canvas shows, also as text on the page's hidden #status element (data-KEY): the model's
// name, the views, the colour range, the pick readout, where the pole markers and the buttons are.
// Screen readers and the tests (tests/web/walkthrough.mjs) read it; set only when it changed.
void publishStatus(const char* key, const std::string& value) {
  static std::map<std::string, std::string> published;
  std::string& known = published[key];
  if (known == value && !value.empty()) return;
  known = value;
  EM_ASM({
    const status = document.getElementById('status');
    if (status) status.dataset[UTF8ToString($0)] = UTF8ToString($1);
  }, key, value.c_str());
}

std::string rectJson(const ImVec2& min, const ImVec2& max) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "[%.1f,%.1f,%.1f,%.1f]", min.x, min.y, max.x, max.y);
  return buffer;
}

class WebApp {
 public:
  bool start();
  void frame();
  // keepCamera: the address's model= (its camera= stays); otherwise the new model is framed.
  void loadObj(const std::string& path, const std::string& name, bool keepCamera);
  void applyQuery(const std::string& query);

 private:
  void panels();
  void overlay(const std::vector<ScreenRect>& rects, const ScreenRect& area);
  void handleInput(const std::vector<ScreenRect>& rects);
  void frameCamera(const ScreenRect& view);
  OrbitCamera& cameraOf(size_t view) { return linkCameras_ ? camera_ : cameras_[view]; }
  WebDraw drawOf(size_t view, const ScreenRect& rect, int framebufferHeight);
  void publishLink();
  void takeScreenshot();

  GLFWwindow* window_ = nullptr;
  WebScene scene_;
  WebRenderer renderer_;
  WebSettings settings_;
  OrbitCamera camera_;  // shared by the views while linked
  std::vector<OrbitCamera> cameras_ = std::vector<OrbitCamera>(kMaxWebViews);
  bool linkCameras_ = true, framed_ = false, firstFrameReported_ = false, screenshot_ = false;
  ShadingParams shading_;
  std::string error_, readout_, link_;
  int readoutView_ = -1;
  glm::dvec3 readoutPoint_{0.0};
  bool hasReadout_ = false;
  ImVec2 pressAt_{0, 0};
};

// [SECTION] Start, model, settings

bool WebApp::start() {
  if (!glfwInit()) return false;
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  const int width = EM_ASM_INT({ return window.innerWidth; }), height = EM_ASM_INT({ return window.innerHeight; });
  window_ = glfwCreateWindow(std::max(width, 64), std::max(height, 64), "polarview", nullptr, nullptr);
  if (!window_) {
    showMessage("WebGL2 is not available in this browser: the viewer cannot draw.");
    return false;
  }
  glfwMakeContextCurrent(window_);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 300 es");
  std::string error;
  if (!renderer_.init(&error)) {
    error_ = error;
    showMessage(error);
  }
  // The default model, then the address's settings (a model= parameter is fetched by the page).
  const std::string loadError = scene_.loadObj("/assets/default.obj", "default model (assets/default.obj)");
  if (!loadError.empty()) error_ = loadError;
  char* query = reinterpret_cast<char*>(EM_ASM_INT({ return allocateUTF8(window.location.search); }));
  applyQuery(query ? query : "");
  free(query);
  return true;
}

void WebApp::applyQuery(const std::string& query) {
  std::vector<std::string> errors;
  settings_ = parseWebQuery(query, &errors);
  shading_.mode = settings_.shade;
  if (settings_.camera) {
    camera_ = *settings_.camera;
    for (OrbitCamera& c : cameras_) c = camera_;
    framed_ = true;
  }
  if (!errors.empty()) {
    std::string text = "address: ";
    for (size_t i = 0; i < errors.size(); ++i) text += (i ? "; " : "") + errors[i];
    error_ = text;
    showMessage(text);
  }
}

void WebApp::loadObj(const std::string& path, const std::string& name, bool keepCamera) {
  const std::string error = scene_.loadObj(path, name);
  if (!error.empty()) {
    // The previous model stays on screen; the message says why the new one is not shown.
    error_ = error;
    showMessage(error);
    return;
  }
  error_.clear();
  showMessage("");
  hasReadout_ = false;
  readout_.clear();
  framed_ = keepCamera && settings_.camera.has_value();
}

// [SECTION] Frame

void WebApp::frame() {
  // Follow the browser window's size.
  const int width = EM_ASM_INT({ return window.innerWidth; }), height = EM_ASM_INT({ return window.innerHeight; });
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  if (w != width || h != height) glfwSetWindowSize(window_, width, height);

  glfwPollEvents();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();

  // Settings -> views (a level the model cannot take is lowered to the deepest that fits).
  int deepest = kMaxLevel;
  for (SchemeChoice scheme : settings_.schemes) deepest = std::min(deepest, scene_.deepestLevel(scheme));
  if (settings_.level > deepest) {
    error_ = "level " + std::to_string(settings_.level) + " is over this page's budget on this model: level " +
             std::to_string(deepest) + " shown";
    showMessage(error_);
    settings_.level = deepest;
  }
  scene_.setViews(settings_.schemes, settings_.level);
  renderer_.upload(scene_);

  const ImGuiIO& io = ImGui::GetIO();
  const float panel = settings_.panels ? kPanelWidth : 0.0f;
  const ScreenRect area{panel, 0.0f, io.DisplaySize.x - panel, io.DisplaySize.y};
  const bool curvature = shading_.mode == ShadingParams::Mode::Gaussian || shading_.mode == ShadingParams::Mode::Mean;
  const bool lines = shading_.mode == ShadingParams::Mode::Highlight || shading_.mode == ShadingParams::Mode::Reflection;
  const float reserve = curvature || lines ? kColourBarStrip : 0.0f;
  const std::vector<ScreenRect> rects = layoutViews(int(settings_.schemes.size()), area, reserve);
  if (!framed_ && scene_.hasModel() && !rects.empty()) frameCamera(rects.front());

  if (settings_.panels) panels();
  handleInput(rects);
  shading_.range = scene_.colourRange(shading_.mode, nullptr);
  overlay(rects, area);

  // Draw: the views, then the panels and overlays over them.
  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
  renderer_.clear(fbWidth, fbHeight);
  for (size_t v = 0; v < rects.size() && v < scene_.views().size(); ++v) renderer_.drawView(v, drawOf(v, rects[v], fbHeight));
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

  if (screenshot_) takeScreenshot();
  publishLink();
  publishStatus("model", scene_.model().name);
  std::string views;
  for (const ViewMesh& view : scene_.views())
    views += (views.empty() ? "" : ";") + std::string(schemeChoiceCliName(view.scheme)) + " level " + std::to_string(view.level) + " " +
             std::to_string(view.indices.size() / 3) + " triangles" + (view.error.empty() ? "" : ": " + view.error);
  publishStatus("views", views);
  char range[80];
  std::snprintf(range, sizeof range, "%.9g %.9g", shading_.range.low, shading_.range.high);
  publishStatus("range", range);
  publishStatus("pick", readout_);
  publishStatus("error", error_);
  if (!firstFrameReported_ && !scene_.views().empty() && ImGui::GetFrameCount() >= 2) {
    // ImGui draws auto-sized windows from their second frame: the page is complete from here.
    firstFrameReported_ = true;
    EM_ASM({ if (window.pvFirstFrame) window.pvFirstFrame(); });
  }
}

void WebApp::frameCamera(const ScreenRect& view) {
  // The desktop's frameModel: the control points in the view's middle, clear of its title.
  const double aspect = double(view.w) / std::max(double(view.h), 1.0);
  const double heightFraction = std::max(0.5, 1.0 - 2.0 * double(kTitleHeight) / std::max(double(view.h), 1.0));
  const std::vector<Point>& points = scene_.model().mesh->points;
  camera_.framePoints(points.data(), points.size(), aspect, heightFraction);
  for (OrbitCamera& c : cameras_) c = camera_;
  framed_ = true;
}

WebDraw WebApp::drawOf(size_t view, const ScreenRect& rect, int framebufferHeight) {
  // The camera relative to the model centre: float keeps its precision near the model.
  OrbitCamera camera = cameraOf(view);
  camera.target -= scene_.centre();
  const double aspect = double(rect.w) / std::max(double(rect.h), 1.0);
  const glm::dmat4 viewMatrix = camera.viewMatrix();
  const glm::dmat4 proj = camera.projectionMatrix(aspect, glm::dvec3(0.0), scene_.radius());
  WebDraw draw;
  // The vertices are in units of scene_.unit() (web_scene.h): so are the eye and the radius.
  const double unit = scene_.unit();
  // Clip coordinates divided by `unit` too (homogeneous: the same picture and depth), so w is about
  // the eye distance in units of `unit`: float-sized at any model scale. Unscaled, a model of size
  // 1e20 gave w ~ 1e20, whose square the rasteriser's interpolation overflows (noisy depth).
  draw.viewProjection = glm::mat4((1.0 / unit) * (proj * viewMatrix * glm::scale(glm::dmat4(1.0), glm::dvec3(unit))));
  draw.viewRotation = glm::mat3(glm::mat4(viewMatrix));
  draw.eye = glm::vec3(camera.eye() / unit);
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  draw.viewport = glm::ivec4(int(rect.x * scale), framebufferHeight - int((rect.y + rect.h) * scale), int(rect.w * scale),
                             int(rect.h * scale));
  draw.radius = float(scene_.radius() / unit);
  draw.curvatureUnit = unit;
  draw.shading = shading_;
  return draw;
}

// [SECTION] Input: orbit, pan, zoom, pick

void WebApp::handleInput(const std::vector<ScreenRect>& rects) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  const ImVec2 mouse = io.MousePos;
  size_t view = rects.size();
  for (size_t v = 0; v < rects.size(); ++v)
    if (rects[v].contains(mouse.x, mouse.y)) view = v;
  if (view == rects.size()) return;
  OrbitCamera& camera = cameraOf(view);
  const ScreenRect& rect = rects[view];
  bool moved = false;
  if (ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1)) pressAt_ = mouse;
  if (ImGui::IsMouseDown(0) && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
    moved = true;
  }
  if ((ImGui::IsMouseDown(1) || ImGui::IsMouseDown(2)) && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    camera.pan(io.MouseDelta.x, io.MouseDelta.y, rect.h);
    moved = true;
  }
  if (io.MouseWheel != 0.0f) {
    const double ndcX = 2.0 * (mouse.x - rect.x) / rect.w - 1.0, ndcY = 1.0 - 2.0 * (mouse.y - rect.y) / rect.h;
    camera.zoomAt(io.MouseWheel, ndcX, ndcY, double(rect.w) / std::max(double(rect.h), 1.0));
    moved = true;
  }
  (void)moved;
  // A click (no drag): the readout of the surface point under the cursor.
  if (ImGui::IsMouseReleased(0) && std::hypot(mouse.x - pressAt_.x, mouse.y - pressAt_.y) < 3.0f) {
    OrbitCamera relative = camera;
    relative.target -= scene_.centre();
    const double aspect = double(rect.w) / std::max(double(rect.h), 1.0);
    const glm::dmat4 inverse = glm::inverse(relative.projectionMatrix(aspect, glm::dvec3(0.0), scene_.radius()) * relative.viewMatrix());
    const double ndcX = 2.0 * (mouse.x - rect.x) / rect.w - 1.0, ndcY = 1.0 - 2.0 * (mouse.y - rect.y) / rect.h;
    const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, -1.0, 1.0), farPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w, direction = glm::dvec3(farPoint) / farPoint.w - origin;
    if (std::optional<PointReadout> readout = scene_.pick(int(view), origin, direction)) {
      readout_ = std::string(schemeChoiceLabel(settings_.schemes[view])) + " view:\n" + readout->text();
      readoutView_ = int(view);
      readoutPoint_ = readout->point.position;
      hasReadout_ = true;
    } else {
      readout_ = "no surface under the cursor";
      hasReadout_ = false;
    }
  }
}

// [SECTION] Panels and overlays

void WebApp::panels() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, io.DisplaySize.y));
  ImGui::Begin("polarview", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::TextWrapped("%s", scene_.model().name.c_str());
  if (ImGui::Button("Open OBJ...")) EM_ASM({ document.getElementById('file').click(); });
  std::string buttons = "{\"open\":" + rectJson(ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
  ImGui::SameLine();
  ImGui::TextDisabled("or drop a file on the page");
  if (!error_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", error_.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::Separator();

  // Views: 1..4, a scheme each.
  int count = int(settings_.schemes.size());
  if (ImGui::SliderInt("views", &count, 1, kMaxWebViews)) {
    const SchemeChoice order[kMaxWebViews] = {SchemeChoice::C2PS, SchemeChoice::CatmullClark, SchemeChoice::RTS, SchemeChoice::BPS};
    while (int(settings_.schemes.size()) < count) settings_.schemes.push_back(order[settings_.schemes.size()]);
    settings_.schemes.resize(size_t(count));
  }
  for (size_t v = 0; v < settings_.schemes.size(); ++v) {
    int choice = int(settings_.schemes[v]);
    const char* labels[kSchemeChoiceCount];
    for (int c = 0; c < kSchemeChoiceCount; ++c) labels[c] = schemeChoiceLabel(SchemeChoice(c));
    ImGui::PushID(int(v));
    if (ImGui::Combo(("view " + std::to_string(v + 1)).c_str(), &choice, labels, kSchemeChoiceCount))
      settings_.schemes[v] = SchemeChoice(choice);
    ImGui::PopID();
  }
  int deepest = kMaxLevel;
  for (SchemeChoice scheme : settings_.schemes) deepest = std::min(deepest, scene_.deepestLevel(scheme));
  ImGui::SliderInt("level", &settings_.level, 0, std::max(deepest, 0));
  if (ImGui::Checkbox("link cameras", &linkCameras_) && !linkCameras_)
    for (OrbitCamera& c : cameras_) c = camera_;
  if (ImGui::Button("Frame model")) framed_ = false;

  // Shading: the desktop's modes and colour maps.
  ImGui::Separator();
  for (const ShadingModeInfo& info : shadingModes()) {
    if (ImGui::RadioButton(info.label, shading_.mode == info.mode)) shading_.mode = info.mode;
  }
  settings_.shade = shading_.mode;
  const char* maps[] = {"paper", "cool-warm", "viridis", "magnitude"};
  int map = int(shading_.colormap);
  if (ImGui::Combo("colour map", &map, maps, 4)) shading_.colormap = ShadingParams::ColorMap(map);

  // Pick readout and the poles' K and H.
  ImGui::Separator();
  ImGui::TextUnformatted("Pick: click the surface");
  if (!readout_.empty()) ImGui::TextWrapped("%s", readout_.c_str());
  ImGui::Separator();
  if (ImGui::CollapsingHeader("Poles: K and H", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (size_t v = 0; v < settings_.schemes.size(); ++v) {
      const std::vector<PoleLine> poles = scene_.poles(settings_.schemes[v], 4);
      if (poles.empty()) {
        ImGui::Text("%s: the model has no poles", schemeChoiceLabel(settings_.schemes[v]));
        break;
      }
      for (const PoleLine& pole : poles) {
        if (pole.curvatureDefined)
          ImGui::Text("%s pole %d (n=%d): K %.6g  H %.6g", schemeChoiceLabel(settings_.schemes[v]), pole.vertex, pole.valence,
                      pole.K, pole.H);
        else
          ImGui::TextWrapped("%s pole %d (n=%d): %s", schemeChoiceLabel(settings_.schemes[v]), pole.vertex, pole.valence,
                             pole.note.c_str());
      }
    }
  }
  ImGui::Separator();
  if (ImGui::Button("Screenshot (PNG)")) screenshot_ = true;
  buttons += ",\"screenshot\":" + rectJson(ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
  ImGui::SameLine();
  if (ImGui::Button("Copy link")) EM_ASM({ if (window.pvCopyLink) window.pvCopyLink(); });
  buttons += ",\"copyLink\":" + rectJson(ImGui::GetItemRectMin(), ImGui::GetItemRectMax()) + "}";
  publishStatus("buttons", buttons);
  for (size_t v = 0; v < scene_.views().size(); ++v) {
    const ViewMesh& view = scene_.views()[v];
    ImGui::TextDisabled("%s: %zu triangles, %d samples/edge, %.0f ms", schemeChoiceLabel(view.scheme), view.indices.size() / 3,
                        view.samples, view.buildMs);
  }
  ImGui::End();
}

void WebApp::overlay(const std::vector<ScreenRect>& rects, const ScreenRect& area) {
  ImDrawList* list = ImGui::GetForegroundDrawList();
  ImFont* font = ImGui::GetFont();
  const float fontSize = ImGui::GetFontSize();
  // Titles, the separating lines, pole markers and the picked point.
  std::string poleMarkers = "[";
  for (size_t v = 0; v < rects.size() && v < scene_.views().size(); ++v) {
    const ScreenRect& r = rects[v];
    const ViewMesh& view = scene_.views()[v];
    std::string title = std::string(schemeChoiceLabel(view.scheme)) + ", level " + std::to_string(view.level);
    if (!view.error.empty()) title += ": " + view.error;
    const ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, r.w - 20.0f, title.c_str());
    const ImVec2 at(r.x + 0.5f * (r.w - size.x), r.y + 8.0f);
    list->AddRectFilled(ImVec2(at.x - 6, at.y - 3), ImVec2(at.x + size.x + 6, at.y + size.y + 3), kOverlayBox, 4.0f);
    list->AddText(font, fontSize, at, view.error.empty() ? kOverlayText : IM_COL32(255, 120, 110, 255), title.c_str(), nullptr,
                  r.w - 20.0f);
    if (v > 0) list->AddLine(ImVec2(r.x, r.y), ImVec2(r.x, r.y + r.h), IM_COL32(110, 110, 115, 255));
    if (!view.surface) continue;
    OrbitCamera camera = cameraOf(v);
    camera.target -= scene_.centre();
    const glm::dmat4 viewProjection = camera.projectionMatrix(double(r.w) / std::max(double(r.h), 1.0), glm::dvec3(0.0), scene_.radius()) *
                                      camera.viewMatrix();
    auto project = [&](const glm::dvec3& p, ImVec2* out) {
      const glm::dvec4 clip = viewProjection * glm::dvec4(p - scene_.centre(), 1.0);
      if (clip.w <= 0.0) return false;
      *out = ImVec2(float(r.x + (clip.x / clip.w * 0.5 + 0.5) * r.w), float(r.y + (0.5 - clip.y / clip.w * 0.5) * r.h));
      return true;
    };
    ImVec2 at2;
    for (const Point& pole : view.surface->poles) {
      if (!project(pole, &at2)) continue;
      list->AddCircle(at2, 7.0f, IM_COL32(0, 0, 0, 200), 20, 3.0f);
      list->AddCircle(at2, 7.0f, IM_COL32(235, 235, 235, 255), 20, 1.5f);
      char marker[64];
      std::snprintf(marker, sizeof marker, "%s[%zu,%.2f,%.2f]", poleMarkers.size() > 1 ? "," : "", v, at2.x, at2.y);
      poleMarkers += marker;
    }
    if (hasReadout_ && readoutView_ == int(v) && project(readoutPoint_, &at2)) {
      list->AddCircle(at2, 8.0f, IM_COL32(0, 0, 0, 200), 20, 3.0f);
      list->AddCircle(at2, 8.0f, IM_COL32(255, 200, 80, 255), 20, 1.5f);
    }
  }
  publishStatus("poles", poleMarkers + "]");
  // One colour bar for every view (the range is shared), with the histogram of the shown values.
  const bool curvature = shading_.mode == ShadingParams::Mode::Gaussian || shading_.mode == ShadingParams::Mode::Mean;
  if (curvature) {
    std::vector<float> bins;
    const ColourInterval range = scene_.colourRange(shading_.mode, &bins);
    const float barWidth = std::min(area.w * 0.6f, 520.0f), barHeight = 14.0f;
    const float left = area.x + 0.5f * (area.w - barWidth);
    const float top = area.y + area.h - kColourBarStrip + 8.0f + kHistogramHeight + 4.0f;
    list->AddRectFilled(ImVec2(left - 40, top - kHistogramHeight - 6), ImVec2(left + barWidth + 40, area.y + area.h - 2), kOverlayBox, 4.0f);
    for (size_t b = 0; b < bins.size(); ++b) {
      const float x0 = left + barWidth * float(b) / float(bins.size()), x1 = left + barWidth * float(b + 1) / float(bins.size());
      const float h = std::sqrt(std::clamp(bins[b], 0.0f, 1.0f)) * kHistogramHeight;
      if (h > 0.0f) list->AddRectFilled(ImVec2(x0 + 0.5f, top - 2 - h), ImVec2(x1 - 0.5f, top - 2), IM_COL32(200, 200, 205, 220));
    }
    auto valueAt = [&](double t) { return colourBarValue(0.5 * (t + 1.0), range); };
    const int segments = 96;
    for (int i = 0; i < segments; ++i) {
      const ImU32 c0 = toImColour(colorMapCpu(shading_.colormap, valueAt(-1.0 + 2.0 * i / segments), range));
      const ImU32 c1 = toImColour(colorMapCpu(shading_.colormap, valueAt(-1.0 + 2.0 * (i + 1) / segments), range));
      const float x0 = left + barWidth * float(i) / segments, x1 = left + barWidth * float(i + 1) / segments;
      list->AddRectFilledMultiColor(ImVec2(x0, top), ImVec2(x1 + 0.5f, top + barHeight), c0, c1, c1, c0);
    }
    list->AddRect(ImVec2(left, top), ImVec2(left + barWidth, top + barHeight), IM_COL32(230, 230, 230, 255));
    for (int t = 0; t <= 4; ++t) {
      const float x = left + barWidth * float(t) / 4.0f;
      const std::string tick = formatTick(valueAt(-1.0 + 2.0 * t / 4.0), std::max(-range.low, range.high));
      const ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, 0.0f, tick.c_str());
      list->AddLine(ImVec2(x, top + barHeight), ImVec2(x, top + barHeight + 4), kOverlayText);
      list->AddText(font, fontSize, ImVec2(x - 0.5f * size.x, top + barHeight + 5), kOverlayText, tick.c_str());
    }
    const std::string title = std::string(shading_.mode == ShadingParams::Mode::Gaussian ? "Gaussian curvature K" : "mean curvature H") +
                              "  (saturates beyond the ends)";
    const ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, 0.0f, title.c_str());
    list->AddText(font, fontSize, ImVec2(left + 0.5f * (barWidth - size.x), top + barHeight + 5 + fontSize), IM_COL32(210, 210, 210, 255),
                  title.c_str());
  } else if (shading_.mode == ShadingParams::Mode::Highlight || shading_.mode == ShadingParams::Mode::Reflection) {
    char legend[160];
    const glm::vec3& d = shading_.highlightDir;
    if (shading_.mode == ShadingParams::Mode::Highlight)
      std::snprintf(legend, sizeof legend, "highlight lines: light direction (%.2f, %.2f, %.2f), spacing %.3g x model radius", d.x, d.y, d.z,
                    shading_.highlightSpacing);
    else
      std::snprintf(legend, sizeof legend, "reflection lines (zebra): stripe direction (%.2f, %.2f, %.2f), period %.3g deg", d.x, d.y,
                    d.z, 360.0f * shading_.reflectionSpacing);
    const ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, 0.0f, legend);
    const ImVec2 at(area.x + 0.5f * (area.w - size.x), area.y + area.h - 0.5f * (kColourBarStrip + size.y));
    list->AddRectFilled(ImVec2(at.x - 8, at.y - 4), ImVec2(at.x + size.x + 8, at.y + size.y + 4), kOverlayBox, 4.0f);
    list->AddText(font, fontSize, at, kOverlayText, legend);
  }
  // Without the panel column, an error still shows (over the views, at the top).
  if (!settings_.panels && !error_.empty()) {
    const ImVec2 size = font->CalcTextSizeA(fontSize, 1e9f, area.w - 40.0f, error_.c_str());
    const ImVec2 at(area.x + 20.0f, area.y + 44.0f);
    list->AddRectFilled(ImVec2(at.x - 6, at.y - 4), ImVec2(at.x + size.x + 6, at.y + size.y + 4), IM_COL32(90, 20, 20, 230), 4.0f);
    list->AddText(font, fontSize, at, IM_COL32(255, 220, 215, 255), error_.c_str(), nullptr, area.w - 40.0f);
  }
}

// [SECTION] Link and screenshot

void WebApp::publishLink() {
  // The address bar always holds the link to what is shown (history.replaceState: no reload).
  const std::string link = makeWebQuery(settings_, camera_);
  if (link == link_) return;
  link_ = link;
  EM_ASM({ if (window.pvSetLink) window.pvSetLink(UTF8ToString($0)); }, link.c_str());
}

void WebApp::takeScreenshot() {
  // Right after drawing, in the same animation frame: the canvas still holds this frame.
  screenshot_ = false;
  std::string name = "polarview";
  for (SchemeChoice scheme : settings_.schemes) name += std::string("_") + schemeChoiceCliName(scheme);
  name += "_level" + std::to_string(settings_.level) + "_" + shadeModeName(shading_.mode) + ".png";
  EM_ASM({ if (window.pvDownloadCanvas) window.pvDownloadCanvas(UTF8ToString($0)); }, name.c_str());
}

WebApp* theApp = nullptr;  // the one instance the page's calls and the browser's frames reach

void frameCallback(void* app) { static_cast<WebApp*>(app)->frame(); }

}  // namespace
}  // namespace polarview

extern "C" {
// The page's entry points (web/index.html): a file written to the in-memory file system by the
// file picker, a drop or a model= address; a new query string.
EMSCRIPTEN_KEEPALIVE void pv_load_obj(const char* path, const char* name, int fromAddress) {
  if (polarview::theApp) polarview::theApp->loadObj(path, name, fromAddress != 0);
}
EMSCRIPTEN_KEEPALIVE void pv_set_query(const char* query) {
  if (polarview::theApp) polarview::theApp->applyQuery(query);
}
}

int main() {
  static polarview::WebApp app;
  if (!app.start()) return 1;
  polarview::theApp = &app;
  emscripten_set_main_loop_arg(polarview::frameCallback, &app, 0, false);
  return 0;
}
