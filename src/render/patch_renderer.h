// PatchRenderer: draws a set of bicubic Patch'es (src/core/spline/patch.h) with GPU tessellation,
// coloured by lighting, Gaussian / mean curvature or highlight / reflection lines, plus overlays
// (control net, patch boundaries, tessellation wireframe, pole markers).
//
// The tessellation evaluation shader mirrors polarview::evaluatePatch (shaders/common/
// patch_eval.glsl, same formulas and names). All GL calls of polarview live in src/render/.
// Every method except the pure CPU ones needs a current GL 4.5 core context (init() first).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/mesh/poly_mesh.h"
#include "core/spline/patch.h"
#include "pipeline/control_net.h"
#include "pipeline/draw_selection.h"
#include "pipeline/shading.h"

namespace polarview {

class ShaderLibrary;

// Statistics of the last draw() (GPU time via a timer query, read back one draw later).
struct DrawStats {
  int patchCount = 0;
  double gpuMilliseconds = 0.0;  // of the draw before the last one; 0 until available
  // The last draw's wall time, from the GL work before it finished to its own finished
  // (glFinish on both ends): on llvmpipe, whose timer queries do not see the work, the view's cost.
  double wallMilliseconds = 0.0;
  // What the view drew (pipeline/draw_selection.h): primitives, the patches they cover (sector
  // groups cover several), and patches culled outside the view.
  size_t drawnPrimitives = 0, drawnPatches = 0, culledPatches = 0;
};

// One tessellation vertex read back from the GPU evaluator (PatchRenderer::probeSurface).
struct SurfaceProbe {
  int patch = 0;           // index into the vector given to setPatches
  float u = 0, v = 0;      // patch parameter
  double gaussian = 0, mean = 0;  // world units (the GPU's values over unit^2 and unit)
  glm::dvec3 position{0.0};  // world coordinates
};

class PatchRenderer {
 public:
  PatchRenderer();
  ~PatchRenderer();
  PatchRenderer(const PatchRenderer&) = delete;
  PatchRenderer& operator=(const PatchRenderer&) = delete;

  // Compiles the shaders and creates the GL objects. Several renderers (one per scheme, drawn in
  // side-by-side viewports) may share one ShaderLibrary; pass nullptr to make a private one.
  // Returns false with the compile log (FILE:LINE) in *error.
  bool init(std::string* error, std::shared_ptr<ShaderLibrary> shaders = nullptr);
  // Re-reads the shader files; on failure keeps the previous programs and returns the log.
  bool reloadShaders(std::string* error);

  // Uploads the patches: each in its own frame (origin at the patch, z along its normal, computed
  // in double) for evaluation, and its control points as double hi + lo floats for the levels, so
  // that deep patches (level 20: 1e-6 of the model) keep float precision relative to their size;
  // with their levels and edge level jumps (Patch::edgeLevelDelta) packed beside the kind, from
  // which patch.tesc gives T-junction edges the same vertices on both sides.
  // Level steps: the first `stableCount` patches are a prefix of a sequence that stays the same
  // across calls with the same `stableStamp` (non-zero; LevelPatchCache's regular patches, level by
  // level): the ones of it already on the GPU, even beyond this set's part (a deeper level shown
  // before), stay there and only the others are packed and uploaded; the rest of the set goes after
  // them. [O(patches not on the GPU) + O(patches) for the level jumps]
  void setPatches(const std::vector<Patch>& patches, uint64_t stableStamp = 0, size_t stableCount = 0);
  // Grows the GPU buffers (keeping what they hold) to take a set of `regular` patches continuing
  // the stable sequence now on the GPU and `other` more: a viewer calls it while idle once the next
  // level is made ahead, so that the step to it does not allocate and copy (on llvmpipe ~100 ms at
  // 250k patches). [O(buffers) GPU copy]
  void reserveFor(size_t regular, size_t other);
  // Patches the last setPatches found on the GPU (not packed, not uploaded). [O(1)]
  size_t lastReusedPatches() const { return reusedPatches_; }
  // Slots of the GPU buffers the set occupies (>= patchCount(): a kept deeper level's). [O(1)]
  size_t slotsInUse() const;
  // Where the patches of the set lie in the GPU buffers (slots), in set order.
  struct DrawRange {
    size_t firstSlot = 0, count = 0, firstIndex = 0;  // firstIndex: of the first patch in the set
  };
  // Uploads the control mesh drawn by DisplayFlags::controlNet (its edges). [O(edges)]
  void setControlMesh(const PolyMesh& mesh);
  // The same with its edges given (control_net.h: each once, crease edges coloured by sharpness).
  void setControlMesh(const PolyMesh& mesh, const std::vector<NetSegment>& segments);
  // Uploads the pole positions drawn by DisplayFlags::poleMarkers.
  void setPoleMarkers(const std::vector<Point>& poles);

  // Draws into the currently bound framebuffer, inside view.viewport (does not clear). Sets
  // glViewport, enables GL_DEPTH_TEST (LEQUAL), disables blending and face culling, and leaves
  // program 0 and VAO 0 bound. Wraps itself in a GL_TIME_ELAPSED query (do not nest another).
  // The first draw in a new shading mode compiles that mode's program (~0.1 s on llvmpipe).
  // [O(patches)]
  void draw(const ViewParams& view, const ShadingParams& shading, const DisplayFlags& flags);
  // The control net alone, over what is in the bound framebuffer (a draw() of the surface without
  // the net just before: its hidden parts faint, as draw() shows it over the surface). For reading
  // the surface's depth in between (pole markers the net's lines would hide). [O(net edges)]
  void drawControlNetOver(const ViewParams& view);

  // Runs the tessellation evaluation shader at a fixed level (every (i/level, j/level) of every
  // patch; caps have one vertex at the pole) and reads position, K, H back by transform feedback.
  // Positions are where draw() places the vertices (relative to the eye, so as precise as floats
  // of their distance to it; ViewParams{}'s eye is (0, 0, 1)), returned in world coordinates.
  std::vector<SurfaceProbe> probeSurface(int tessLevel);
  // The same with the tessellation draw() would use for this view and shading (adaptive levels
  // unless shading.fixedTessLevel > 0): exposes the levels, e.g. to check shared edges match.
  std::vector<SurfaceProbe> probeSurface(const ViewParams& view, const ShadingParams& shading);

  // Per region detail (default on): draw() culls what is outside the view and draws sub-pixel
  // sectors of a polar ring several to a primitive (pipeline/draw_selection.h); off, every patch of
  // the set is drawn alone (the reference picture, render --full-draw). Set it before setPatches,
  // which builds the selection only where it is on.
  void setRegionDetail(bool on) { regionDetail_ = on; }

  // Bounding box of the uploaded patches (their control points / cap positions), world coords.
  glm::dvec3 boundsMin() const { return boundsMin_; }
  glm::dvec3 boundsMax() const { return boundsMax_; }
  glm::dvec3 center() const { return center_; }
  double boundingRadius() const { return radius_; }
  int patchCount() const { return patchCount_; }
  const DrawStats& lastDrawStats() const { return stats_; }
  // Compile log of a shader variant that failed when draw() first needed it ("" if none); such a
  // variant falls back to the plain shaded program.
  const std::string& lastError() const { return lastError_; }

 private:
  struct Impl;
  unsigned surfaceProgram(ShadingParams::Mode mode, bool wireframe, bool groups);
  // setPatches' steps: the bounding box, centre, radius and GPU unit of the set (patches before
  // `first` are already inside the box when `sameSequence`).
  void placeBounds(const std::vector<Patch>& patches, size_t first, bool sameSequence);
  // draw()'s steps: the GL_TIME_ELAPSED query (reading the one of two draws ago), the surface and
  // its uniforms, patch boundary curves, and the overlays in program `overlay`.
  void startGpuTimer();
  void setShadingUniforms(unsigned program, const ViewParams& view, const ShadingParams& shading,
                          const DisplayFlags& flags) const;
  void drawSurface(const ViewParams& view, const ShadingParams& shading, const DisplayFlags& flags);
  // The selected items' texels uploaded, then drawn in runs Mesa counts right: lone patches by
  // `program`, groups of sectors by its SECTOR_GROUPS twin.
  void drawItems(const ViewParams& view, const ShadingParams& shading, const DisplayFlags& flags, unsigned program,
                 std::vector<DrawItem> items);
  void drawPatchBoundaries(const ViewParams& view, const DisplayFlags& flags);
  void drawControlNet(unsigned overlay, bool overSurface);
  void drawPoleMarkers(unsigned overlay);
  // Sets the relative-to-eye uniforms of common/patch_frame.glsl and binds the patch frames.
  void setEyeUniforms(unsigned program, const ViewParams& view) const;
  void setTessellationUniforms(unsigned program, const ViewParams& view,
                               const ShadingParams& shading) const;
  // Per-view density exponent k of T-junction edges (patch.tesc): 2^k segments per level-0
  // parameter unit, so that they are about shading.tessPixels long at the model centre.
  int transitionDensity(const ViewParams& view, const ShadingParams& shading) const;
  std::unique_ptr<Impl> impl_;
  glm::dvec3 boundsMin_{0.0}, boundsMax_{0.0}, center_{0.0};
  double radius_ = 1.0;
  // The GPU's length unit: a power of two near the model's radius. Everything uploaded is in these
  // units (scaled exactly), so models of 1e-150 and 1e150 (the OBJ reader's range) reach the GPU at
  // size ~1: float's range ends at 3e38 and its curvature (1 / length^2) underflowed at 1e-10.
  double unit_ = 1.0;
  int patchCount_ = 0;
  std::vector<DrawRange> drawRanges_;
  DrawSelection selection_;  // the set's rows and bounds, for culling and sector groups
  std::vector<int8_t> turnOfPatch_;  // Patch::ringTurn per patch: the GPU's parameter is turned
  // Whether draws choose their patches per region (culled, sector groups; setRegionDetail).
  bool regionDetail_ = true;
  uint64_t stableStamp_ = 0;  // setPatches' sequence on the GPU, and how many of its slots are valid
  size_t stableOnGpu_ = 0;
  size_t reusedPatches_ = 0;
  int patchIndexOfSlot(size_t slot) const {
    for (const DrawRange& range : drawRanges_)
      if (slot >= range.firstSlot && slot < range.firstSlot + range.count) return int(range.firstIndex + slot - range.firstSlot);
    return -1;
  }
  DrawStats stats_;
  std::string lastError_;
};

}  // namespace polarview
