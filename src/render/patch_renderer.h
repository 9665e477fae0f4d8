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

namespace polarview {

class ShaderLibrary;

// How the surface is coloured.
struct ShadingParams {
  enum class Mode { Shaded, Gaussian, Mean, Highlight, Reflection };
  enum class ColorMap { Paper, CoolWarm, Viridis, Magnitude };  // Magnitude: Figs 11-12, dark blue at 0
  Mode mode = Mode::Shaded;
  ColorMap colormap = ColorMap::Paper;
  float range = 1.0f;            // curvature maps [-range, range]; saturates beyond (paper Fig. 13)
  // > 0: the negative side's range instead, [-rangeBelow, range] with zero still the map's middle
  // (two slopes, as matplotlib's TwoSlopeNorm), so zero curvature keeps its colour.
  float rangeBelow = 0.0f;
  float curvatureLighting = 0.35f;  // 0: flat curvature colour (exact map colour), 1: fully lit
  // Highlight lines (Beier & Chen 1994, SCHEMES.md section 7): parallel light lines with direction
  // highlightDir, lying in a plane of normal highlightPlaneNormal (orthogonalised against the
  // direction) placed 2 bounding radii from the model centre. Spacing is in units of the model's
  // bounding radius; width is the fraction of one spacing that is dark (0..1).
  // Reflection lines (zebra) use the same direction and width, and reflectionSpacing: the stripe
  // period as a fraction of a full turn of the reflected ray (1/24: a stripe pair every 15 degrees,
  // about a dozen stripes across a dome at the default view; 1/4 showed only ~3).
  glm::vec3 highlightDir{1.0f, 0.0f, 0.0f};
  glm::vec3 highlightPlaneNormal{0.0f, 0.0f, 1.0f};
  float highlightSpacing = 0.25f;
  float reflectionSpacing = 1.0f / 24.0f;
  float highlightWidth = 0.3f;
  // Key light of the lit and curvature modes, in view space (x right, y up, z towards the eye):
  // upper left, in front. Ctrl+left drag turns it.
  glm::vec3 keyLightView{-0.35f, 0.55f, 0.76f};
  float tessPixels = 12.0f;   // target screen length of a tessellated edge, in pixels
  int maxTessLevel = 64;      // clamp of the adaptive level (llvmpipe gets ~5x slower from 15 up)
  int fixedTessLevel = 0;     // > 0: this level on every edge instead of the adaptive one
  glm::vec3 surfaceColor{0.78f, 0.80f, 0.84f};  // base colour of Shaded mode
};

// What is drawn.
struct DisplayFlags {
  enum class BoundaryColor { Kind, Ring };
  bool surface = true;
  bool controlNet = false;
  bool patchBoundaries = false;
  bool poleMarkers = true;
  bool wireframe = false;  // tessellation triangles over (or, with surface off, instead of) it
  BoundaryColor boundaryColor = BoundaryColor::Kind;
};

// Camera for one draw. view/proj map world coordinates (the Patch coordinates) to clip space;
// viewport is (x, y, width, height) in framebuffer pixels, bottom-left origin as glViewport.
// The renderer draws relative to the eye (see "Precision" in patch_renderer.cpp): it takes the
// rotation from `view` and the translation from `eye`, which must therefore be the eye of `view`,
// given in double (a float eye would move the camera by its rounding, ~6e-8 of its coordinates).
struct ViewParams {
  glm::mat4 view{1.0f}, proj{1.0f};
  glm::ivec4 viewport{0, 0, 1, 1};
  glm::dvec3 eye{0.0, 0.0, 1.0};  // camera position in world coordinates
};

// Statistics of the last draw() (GPU time via a timer query, read back one draw later).
struct DrawStats {
  int patchCount = 0;
  double gpuMilliseconds = 0.0;  // of the draw before the last one; 0 until available
};

// One tessellation vertex read back from the GPU evaluator (PatchRenderer::probeSurface).
struct SurfaceProbe {
  int patch = 0;           // index into the vector given to setPatches
  float u = 0, v = 0;      // patch parameter
  float gaussian = 0, mean = 0;
  glm::dvec3 position{0.0};  // world coordinates
};

// Colours used for DisplayFlags::BoundaryColor::Kind (index = PatchKind), also for a UI legend.
glm::vec3 patchKindColor(PatchKind kind);
// Colour for a ring index (cycles through a qualitative palette; -1 = grey).
glm::vec3 ringColor(int ring);
// The curvature colour map on the CPU, identical to shaders/common/colormap.glsl: value in
// [-range, range] -> RGB in [0,1]. For legends and tests.
glm::vec3 colorMapCpu(ShadingParams::ColorMap map, float value, float range, float rangeBelow = 0.0f);

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
  // Uploads the pole positions drawn by DisplayFlags::poleMarkers.
  void setPoleMarkers(const std::vector<Point>& poles);

  // Draws into the currently bound framebuffer, inside view.viewport (does not clear). Sets
  // glViewport, enables GL_DEPTH_TEST (LEQUAL), disables blending and face culling, and leaves
  // program 0 and VAO 0 bound. Wraps itself in a GL_TIME_ELAPSED query (do not nest another).
  // The first draw in a new shading mode compiles that mode's program (~0.1 s on llvmpipe).
  // [O(patches)]
  void draw(const ViewParams& view, const ShadingParams& shading, const DisplayFlags& flags);

  // Runs the tessellation evaluation shader at a fixed level (every (i/level, j/level) of every
  // patch; caps have one vertex at the pole) and reads position, K, H back by transform feedback.
  // Positions are where draw() places the vertices (relative to the eye, so as precise as floats
  // of their distance to it; ViewParams{}'s eye is (0, 0, 1)), returned in world coordinates.
  std::vector<SurfaceProbe> probeSurface(int tessLevel);
  // The same with the tessellation draw() would use for this view and shading (adaptive levels
  // unless shading.fixedTessLevel > 0): exposes the levels, e.g. to check shared edges match.
  std::vector<SurfaceProbe> probeSurface(const ViewParams& view, const ShadingParams& shading);

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
  unsigned surfaceProgram(ShadingParams::Mode mode, bool wireframe);
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
  int patchCount_ = 0;
  std::vector<DrawRange> drawRanges_;
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

// Curvature samples of patches for the auto range (CPU, via evaluatePatch): samplesPerPatch^2
// values K (mode Gaussian) or H (mode Mean) per patch at cell centres. [O(patches * samples^2)]
std::vector<float> sampleCurvature(const std::vector<Patch>& patches, ShadingParams::Mode mode,
                                   int samplesPerPatch);
// A symmetric colour-map range that covers `quantile` (e.g. 0.95) of |values|; 1 when empty or 0.
float suggestCurvatureRange(std::vector<float> values, float quantile);

}  // namespace polarview
