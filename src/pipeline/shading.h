// What a view draws and how, as plain data (no GL): shading mode and colour map, display flags,
// the camera of one draw, and the colours the shaders use, mirrored on the CPU for legends, tests
// and images. PatchRenderer (render/) takes these; the panels (ui/) edit them.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

#include "core/spline/patch.h"

namespace polarview {

// The values a curvature colour map spans, [low, high], saturating beyond. With zero inside
// (low < 0 < high) zero is the map's middle with two slopes (matplotlib's TwoSlopeNorm), so zero
// keeps its colour: the paper's Fig. 13. Otherwise the range is one-sided: [low, high] spans the
// half of the map of its sign, linearly (all K > 0 in green .. red), so one-signed values still
// show their variation (docs/shading.md#colour-maps).
struct ColourInterval {
  double low = -1.0, high = 1.0;
  bool oneSided() const { return !(low < 0.0 && high > 0.0); }
  static ColourInterval symmetric(double range) { return {-range, range}; }
  bool operator==(const ColourInterval& o) const { return low == o.low && high == o.high; }
  bool operator!=(const ColourInterval& o) const { return !(*this == o); }
};
// Where `value` lies along the colour bar, in [0, 1] (clamped). [O(1)]
double colourBarPosition(double value, const ColourInterval& range);
// The value at bar position p in [0, 1] (the inverse of colourBarPosition). [O(1)]
double colourBarValue(double position, const ColourInterval& range);

// What the automatic colour range is made of, from area-weighted values of K or H: the viewer's
// shown samples (session) and the tessellations' vertices (export to ply, glb) read the same rule.
struct ColourStatistics {
  double symmetricRange = 1.0;  // weightedSymmetricRange
  ColourInterval percentiles;   // [P(1 - q), P(q)]; one-signed values all equal: widened to 1e-6 of them
  double min = -1.0, max = 1.0; // the values' extremes (which decide whether all have one sign)
  // All values >= 0 (1) or <= 0 (-1), not all zero; 0 when mixed. [O(1)]
  int oneSign() const { return min >= 0.0 && max > 0.0 ? 1 : max <= 0.0 && min < 0.0 ? -1 : 0; }
  // The automatic range: one-sided `percentiles` for one-signed values, else +-symmetricRange. [O(1)]
  ColourInterval automaticInterval() const {
    return oneSign() != 0 ? percentiles : ColourInterval::symmetric(symmetricRange);
  }
};
// The statistics of non-empty `values` with `weights` for the upper percentile `quantile` (0.9: the
// 10th and 90th). [O(n log n)]
ColourStatistics colourStatistics(const std::vector<double>& values, const std::vector<double>& weights, float quantile);

// How the surface is coloured.
struct ShadingParams {
  enum class Mode { Shaded, Gaussian, Mean, Highlight, Reflection };
  enum class ColorMap { Paper, CoolWarm, Viridis, Magnitude };  // Magnitude: Figs 11-12, dark blue at 0
  Mode mode = Mode::Shaded;
  ColorMap colormap = ColorMap::Paper;
  ColourInterval range;          // what the curvature maps span; saturates beyond (paper Fig. 13)
  float curvatureLighting = 0.35f;  // 0: flat curvature colour (exact map colour), 1: fully lit
  // Highlight lines (Beier & Chen 1994, docs/shading.md): parallel light lines with direction
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

// The shading modes, a row each: the name the command line and the viewer's commands use, the
// panels' label and key, and what the mode draws. A new mode is a row here (and its enum value
// above) plus its branch in shaders/patch.frag.
struct ShadingModeInfo {
  ShadingParams::Mode mode;
  const char* name;   // "gaussian": `--shade gaussian`, the command shade.gaussian
  const char* alias;  // another accepted name ("lit", "zebra"), or ""
  const char* label;  // "Gaussian K"
  char key;           // 'G'
  bool curvature;     // a colour map of K or H: the colour bar and its range
  bool lightLines;    // highlight or reflection lines: the light-line legend and controls
};
const std::vector<ShadingModeInfo>& shadingModes();
const ShadingModeInfo& shadingModeInfo(ShadingParams::Mode mode);

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
  glm::dmat4 view{1.0}, proj{1.0};  // double: a model of 1e40 is past float's range
  glm::ivec4 viewport{0, 0, 1, 1};
  glm::dvec3 eye{0.0, 0.0, 1.0};  // camera position in world coordinates
};

// Colours used for DisplayFlags::BoundaryColor::Kind (index = PatchKind), also for a UI legend.
// The unit vector perpendicular to `axis` (unit) nearest to `hint`: the plane the highlight lines
// lie in (highlightPlaneNormal made perpendicular to highlightDir), for the desktop's and the web
// page's renderers alike. [O(1)]
glm::vec3 perpendicularTo(const glm::vec3& axis, const glm::vec3& hint);
glm::vec3 patchKindColor(PatchKind kind);
// Colour for a ring index (cycles through a qualitative palette; -1 = grey).
glm::vec3 ringColor(int ring);
// The curvature colour map on the CPU, identical to shaders/common/colormap.glsl: value in
// `range` -> RGB in [0,1]. For legends and tests.
glm::vec3 colorMapCpu(ShadingParams::ColorMap map, double value, const ColourInterval& range);
// The same for the symmetric range [-range, range].
inline glm::vec3 colorMapCpu(ShadingParams::ColorMap map, double value, double range) {
  return colorMapCpu(map, value, ColourInterval::symmetric(range));
}

// Area-weighted histogram over the colour bar of `range` (two slopes or one-sided, as the map:
// colourBarPosition; values beyond go to the end bins), scaled so the largest bin is 1. [O(n)]
std::vector<float> weightedHistogram(const std::vector<double>& values, const std::vector<double>& weights,
                                     const ColourInterval& range, int bins);

}  // namespace polarview
