// The window's GPU copy of the session's surfaces (gpu_mirror.h).
#include "app/gpu_mirror.h"

#include "session/settings_rules.h"

#include "pipeline/stopwatch.h"
#include "pipeline/model.h"
#include "pipeline/surface_build.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "render/gl_context.h"
#include "render/shader_library.h"

namespace polarview {

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

namespace {

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

}  // namespace

GpuMirror::GpuMirror(std::shared_ptr<ShaderLibrary> shaders, LevelOfDetail levelOfDetail)
    : shaders_(std::move(shaders)), levelOfDetail_(levelOfDetail) {
  for (GpuView& view : views_) view.shown.renderer = makeRenderer();
}

GpuMirror::~GpuMirror() = default;

std::unique_ptr<PatchRenderer> GpuMirror::makeRenderer() const {
  auto renderer = std::make_unique<PatchRenderer>();
  std::string log;
  if (!renderer->init(&log, shaders_)) throw std::runtime_error("shaders: " + log);  // compiled once already
  renderer->setRegionDetail(levelOfDetail_.enabled);  // render --full-draw: every patch alone
  return renderer;
}

GpuMirror::UploadCost GpuMirror::upload(int v, const BuiltSurface& surface, const ViewerSettings& settings) {
  GpuSlot& slot = views_[size_t(v)].shown;
  // A level step on the same hierarchy keeps the patches both levels share on the GPU.
  const auto start = std::chrono::steady_clock::now();
  const int zoom = surface.poles.empty() ? -1 : settings.poleInspector.zoomRing;
  if (zoom >= 0) {
    // Pole zoom: the rings of the inspected pole, scaled in double (a new upload: no stable prefix).
    const int pole = std::clamp(settings.poleInspector.pole, 0, int(surface.poles.size()) - 1);
    slot.renderer->setPatches(zoomAboutPole(surface.patches, pole, zoom, 3, surface.poles[size_t(pole)]));
  } else {
    slot.renderer->setPatches(surface.patches, surface.stamp, surface.regularCount);
  }
  slot.zoom = zoom;
  return {millisecondsSince(start), slot.renderer->lastReusedPatches()};
}

double GpuMirror::sync(int v, SurfaceCache& surfaces, const ViewerSettings& settings, ViewerStatus& status,
                       const Model& model, double firstPixelsHigh) {
  GpuView& gpu = views_[size_t(v)];
  const std::shared_ptr<const BuiltSurface>& shown = surfaces.shown(v);
  const std::shared_ptr<const BuiltSurface>& parked = surfaces.parked(v);
  // Each renderer keeps what it draws: a scheme toggle back swaps them (nothing uploaded).
  const auto swapStart = std::chrono::steady_clock::now();
  const bool swapped = shown && gpu.parked.surface == shown;
  if (swapped) std::swap(gpu.shown, gpu.parked);
  if (std::optional<GpuReservation> room = surfaces.takeReservation(v)) {
    if (!gpu.shown.renderer) gpu.shown.renderer = makeRenderer();
    gpu.shown.renderer->reserveFor(room->regularPatches, room->capPatches);
  }
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
  const int zoom = !shown || shown->poles.empty() ? -1 : settings.poleInspector.zoomRing;
  if (!shown || (gpu.shown.surface == shown && gpu.shown.zoom == zoom)) return 0.0;
  // What the level of detail draws of it goes up (all of it where it picks the surface's level).
  std::shared_ptr<const BuiltSurface> drawn;
  const double pixelsHigh = gpu.pixelsHigh > 0.0 ? gpu.pixelsHigh : firstPixelsHigh;
  if (pixelsHigh > 0.0 && zoom < 0) {
    const int wanted = levelOfDetail(v, *shown, pixelsHigh, settings, status, model);
    if (wanted < shown->patchLevel) drawn = drawnSurface(*shown, model, wanted);
  }
  const UploadCost cost = upload(v, drawn ? *drawn : *shown, settings);
  gpu.uploadMs = cost.milliseconds;  // the Stats panel's: a later level-of-detail switch does not count
  gpu.keptPatches = surfaces.refreshed(v) ? 0 : cost.keptPatches;  // moved points: no patch stayed
  gpu.shown.surface = shown;
  gpu.shown.drawn = std::move(drawn);
  gpu.shown.renderer->setControlMesh(shown->controlMesh, shown->netSegments);
  gpu.shown.renderer->setPoleMarkers(shown->poles);
  return cost.milliseconds;
}

void GpuMirror::report(int v, ViewStatus& status) const {
  const GpuView& gpu = views_[size_t(v)];
  status.uploadMs = gpu.uploadMs;
  status.keptPatches = int(gpu.keptPatches);
  status.zoomRing = gpu.shown.zoom;
  if (const BuiltSurface* shown = gpu.shown.surface.get()) {
    status.drawnLevel = gpu.shown.drawn ? gpu.shown.drawn->patchLevel : shown->patchLevel;
    status.drawnPatches = int(gpu.shown.drawn ? gpu.shown.drawn->patches.size() : shown->patches.size());
  }
}

int GpuMirror::levelOfDetail(int v, const BuiltSurface& shown, double pixelsHigh, const ViewerSettings& settings,
                             const ViewerStatus& status,
                             const Model& model) const {
  // While a drag moves points every frame the full set is drawn (each new set would be assembled anew).
  if (!levelOfDetail_.enabled || status.edit.dragging || shown.key.points != model.points) return shown.patchLevel;
  return levelToDraw(shown.detail, shown.patchLevel, settings.camera(v), pixelsHigh, levelOfDetail_.pixels);
}

void GpuMirror::updateDrawnLevel(int v, double pixelsHigh, const ViewerSettings& settings, ViewerStatus& status,
                                 const Model& model) {
  GpuSlot& slot = views_[size_t(v)].shown;
  const BuiltSurface* shown = slot.surface.get();
  if (!shown || slot.zoom >= 0) return;
  const int wanted = levelOfDetail(v, *shown, pixelsHigh, settings, status, model);
  const int drawnNow = slot.drawn ? slot.drawn->patchLevel : shown->patchLevel;
  if (wanted != drawnNow) {
    std::shared_ptr<const BuiltSurface> drawn = wanted < shown->patchLevel ? drawnSurface(*shown, model, wanted) : nullptr;
    if (wanted >= shown->patchLevel || drawn) {  // else not available now (an edit is applied): keep
      upload(v, drawn ? *drawn : *shown, settings);
      slot.drawn = std::move(drawn);
    }
  }
  ViewStatus& reported = status.views[size_t(v)];
  reported.drawnLevel = slot.drawn ? slot.drawn->patchLevel : shown->patchLevel;
  reported.drawnPatches = int(slot.drawn ? slot.drawn->patches.size() : shown->patches.size());
}

std::vector<PoleMarker> GpuMirror::draw(const std::vector<ScreenRect>& rects, float pixelScale, int framebufferHeight,
                                        const ViewerSettings& settings, ViewerStatus& status, const Document& document) {
  const glm::dvec3 centre = 0.5 * (document.modelMin() + document.modelMax());
  const double radius = 0.5 * glm::length(document.modelMax() - document.modelMin());
  ShadingParams shading = settings.shading;
  std::vector<PoleMarker> markers;
  for (size_t v = 0; v < rects.size(); ++v) {
    const GpuSlot& gpu = views_[v].shown;
    if (!gpu.surface) continue;
    // Each view in its own style where it has one (render --shade a,b; figures), else the shared one.
    shading.mode = settings.viewShade(int(v));
    // A pole zoom by s = 2^m scales K by 1 / s^2 and H by 1 / s: the range alike, so colours keep values.
    shading.range = colourInterval(settings, status);
    if (gpu.zoom >= 0) {
      const float s = std::ldexp(1.0f, gpu.zoom);
      const float scale = shading.mode == ShadingParams::Mode::Gaussian ? 1.0f / (s * s) : 1.0f / s;
      shading.range = {shading.range.low * scale, shading.range.high * scale};
    }
    // Poles are marked by rings in the overlay, not by the renderer's filled discs (which read
    // like a curvature feature right at the pole).
    DisplayFlags display = settings.viewDisplay(int(v));
    const bool markPoles = display.poleMarkers;
    display.poleMarkers = false;
    const ScreenRect& r = rects[v];
    const OrbitCamera& camera = settings.camera(int(v));
    views_[v].pixelsHigh = double(r.h) * pixelScale;
    updateDrawnLevel(int(v), views_[v].pixelsHigh, settings, status, document.model());
    ViewParams params;
    params.viewport = glm::ivec4(int(r.x * pixelScale), framebufferHeight - int((r.y + r.h) * pixelScale),
                                 int(r.w * pixelScale), int(r.h * pixelScale));
    params.view = camera.viewMatrix();
    params.proj = camera.projectionMatrix(double(r.w) / std::max(double(r.h), 1.0), centre, radius);
    params.eye = camera.eye();  // double: the renderer draws relative to the eye
    // The poles' visibility is read from the surface's depth before the control net is drawn: the
    // net's lines meet at the pole vertex, in front of the limit pole, and hid every marker.
    const bool netAfter = markPoles && display.controlNet && display.surface;
    DisplayFlags first = display;
    if (netAfter) first.controlNet = false;
    gpu.renderer->draw(params, shading, first);
    const DrawStats& drew = gpu.renderer->lastDrawStats();
    ViewStatus& reported = status.views[v];
    reported.drawnPrimitives = int(drew.drawnPrimitives);
    reported.visiblePatches = int(drew.drawnPatches);
    reported.culledPatches = int(drew.culledPatches);
    reported.drawMs = drew.wallMilliseconds;
    // A pole zoom draws that pole's rings scaled about it: its marker stays, the others are not there.
    if (markPoles) {
      std::vector<Point> poles = gpu.surface->poles;
      if (gpu.zoom >= 0 && !poles.empty())
        poles = {poles[size_t(std::clamp(settings.poleInspector.pole, 0, int(poles.size()) - 1))]};
      visiblePoles(poles, params, camera.eye(), 0.02 * radius, pixelScale, framebufferHeight, &markers);
    }
    if (netAfter) gpu.renderer->drawControlNetOver(params);
  }
  return markers;
}

}  // namespace polarview
