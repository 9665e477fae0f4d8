// The window's GPU copy of the session's surfaces: per view a renderer holding what the shown
// surface draws and one holding the parked surface's (a scheme toggle back swaps the two, nothing
// uploaded), keyed by the surfaces the cache holds (session/surface_cache.h) and by the pole zoom.
// A level step uploads only the patches the GPU does not hold (PatchRenderer::setPatches' prefix);
// where deeper rings are below a pixel the shallower level is drawn (pipeline/level_of_detail.h).
// Needs the GL context: the window application owns it.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/patch_renderer.h"
#include "session/document.h"
#include "session/surface_cache.h"
#include "ui/viewer_panels.h"
#include "pipeline/model.h"
#include "pipeline/surface_build.h"

namespace polarview {

class ShaderLibrary;

class GpuMirror {
 public:
  struct LevelOfDetail {
    bool enabled = true;  // draw the shallowest level that looks the same but for `pixels` at each feature
    double pixels = 3.0;
  };
  // One renderer per view over one shader library. Throws when the shaders do not compile.
  GpuMirror(std::shared_ptr<ShaderLibrary> shaders, LevelOfDetail levelOfDetail);
  ~GpuMirror();

  // Brings view v's renderers to the cache's shown and parked surfaces: swaps, drops or uploads
  // (and reserves room for a level made ahead). Returns the milliseconds an upload took (0 when
  // none). [O(patches not on the GPU)]
  // A new surface goes up as the level of detail would draw it at the view's camera and last size
  // (`firstPixelsHigh` before its first draw): its shallower set where deeper rings are below a
  // pixel (the first C2PS 12 build uploads the 3,800-8,000 patches drawn, not all 246,000).
  double sync(int v, SurfaceCache& surfaces, const ViewerSettings& settings, ViewerStatus& status, const Model& model,
              double firstPixelsHigh);
  // The GPU's part of view v's status: upload time, patches kept, pole zoom, level drawn.
  void report(int v, ViewStatus& status) const;
  // Draws the views into the bound framebuffer; returns the pole markers the surfaces leave visible
  // (overlay coordinates: framebuffer pixels / pixelScale, y down).
  std::vector<PoleMarker> draw(const std::vector<ScreenRect>& rects, float pixelScale, int framebufferHeight,
                               const ViewerSettings& settings, ViewerStatus& status, const Document& document);
  // View v's renderer of the shown surface (what is on the GPU), for tests.
  const PatchRenderer& renderer(int v) const { return *views_[size_t(v)].shown.renderer; }

 private:
  // A renderer and what it holds: a surface's patches, or the shallower set `drawn` where deeper
  // rings are below a pixel, or a pole zoom's rings.
  struct GpuSlot {
    std::unique_ptr<PatchRenderer> renderer;
    std::shared_ptr<const BuiltSurface> surface, drawn;
    int zoom = -1;  // the pole zoom ring it holds (-1: the whole surface)
  };
  struct GpuView {
    GpuSlot shown, parked;
    double uploadMs = 0.0;   // the last upload of the shown surface: packing + upload
    double pixelsHigh = 0.0; // the view's height at its last draw (0: not drawn yet)
    size_t keptPatches = 0;  // patches of it that stayed on the GPU
  };
  struct UploadCost {
    double milliseconds = 0.0;
    size_t keptPatches = 0;
  };
  std::unique_ptr<PatchRenderer> makeRenderer() const;
  // Uploads `surface`'s patches to view v's shown renderer (a pole zoom: its zoomed rings).
  UploadCost upload(int v, const BuiltSurface& surface, const ViewerSettings& settings);
  // Draws the level levelToDraw picks for the view's camera (viewport `pixelsHigh` high): switches
  // `drawn` when it changes. [O(features) a frame; O(patches of the set) on a switch]
  void updateDrawnLevel(int v, double pixelsHigh, const ViewerSettings& settings, ViewerStatus& status, const Model& model);
  // The level levelToDraw picks for `shown` in view v now (its level when the level of detail is off,
  // a drag is on or the points moved).
  int levelOfDetail(int v, const BuiltSurface& shown, double pixelsHigh, const ViewerSettings& settings,
                    const ViewerStatus& status, const Model& model) const;

  std::shared_ptr<ShaderLibrary> shaders_;
  LevelOfDetail levelOfDetail_;
  std::array<GpuView, kMaxViews> views_;
};

// Window coordinates (x, y in pixels, z the depth in [0, 1]) of `world`, and back, in double and
// relative to the eye: at a deep pole the points differ from the eye by 1e-6 of their coordinates,
// which float (glm::project's) would round away. `rotation`: the view matrix without translation.
glm::dvec3 windowOf(const glm::dvec3& world, const glm::dvec3& eye, const glm::dmat4& rotation, const glm::dmat4& proj,
                    const glm::dvec4& viewport);
glm::dvec3 worldOf(const glm::dvec3& window, const glm::dvec3& eye, const glm::dmat4& rotation, const glm::dmat4& proj,
                   const glm::dvec4& viewport);
glm::dmat4 rotationOf(const glm::mat4& view);

}  // namespace polarview
