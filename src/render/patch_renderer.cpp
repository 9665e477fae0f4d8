// PatchRenderer: GPU tessellation of bicubic patches with curvature / highlight shading and
// overlays (see patch_renderer.h). Shaders: shaders/patch.*, patch_boundary.*, overlay.*.
#include "render/patch_renderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>

#include "render/shader_library.h"

namespace polarview {
namespace {

constexpr int kControlPointsPerPatch = 16;

// Patch kinds whose control points are all positions (everything but the PoleCap).
bool isPositionSlot(PatchKind kind, int slot) {
  if (kind != PatchKind::PoleCap) return true;
  return slot == 0 || (slot >= 6 && slot <= 9);  // p0 and the boundary curve b_{j-1..j+2}
}

// The kind attribute's x as patch.tesc unpacks it: bits 0-7 PatchKind, 8-15 level, then
// Patch::edgeLevelDelta of edges 0..3 as signed 4-bit fields at bits 16 + 4s (jumps beyond
// [-8, 7] get the same tessellation as those ends, see transitionEdgeSegments).
int32_t packKindLevelJumps(const Patch& patch) {
  uint32_t packed = uint32_t(patch.kind) | uint32_t(patch.level) << 8;
  for (int s = 0; s < 4; ++s)
    packed |= (uint32_t(std::clamp(int(patch.edgeLevelDelta[s]), -8, 7)) & 0xFu) << (16 + 4 * s);
  return static_cast<int32_t>(packed);
}

// World length of one level-0 parameter unit along the T-junction edges: the mean over their
// coarse sides of chord * 2^level (chord between the face's corner control points); 0 if none.
double transitionUnitLength(const std::vector<Patch>& patches) {
  static constexpr int kEdgeCorners[4][2] = {{5, 6}, {6, 10}, {10, 9}, {9, 5}};  // patch.h order
  double sum = 0.0;
  int sides = 0;
  for (const Patch& patch : patches) {
    if (patch.kind == PatchKind::PoleCap) continue;
    for (int s = 0; s < 4; ++s)
      if (patch.edgeLevelDelta[s] > 0) {
        sum += std::ldexp(glm::length(patch.cp[kEdgeCorners[s][0]] - patch.cp[kEdgeCorners[s][1]]), patch.level);
        ++sides;
      }
  }
  return sides > 0 ? sum / sides : 0.0;
}

// Program specs: every shader file and variant the renderer uses.
// One surface program per shading mode (a #define, so llvmpipe runs no per-pixel mode branches),
// with or without the wireframe geometry shader.
ProgramSpec surfaceSpec(ShadingParams::Mode mode, bool wireframe) {
  ProgramSpec spec;
  spec.vertex = "patch.vert";
  spec.tessControl = "patch.tesc";
  spec.tessEval = "patch.tese";
  spec.fragment = "patch.frag";
  spec.defines = {"SHADING_MODE " + std::to_string(static_cast<int>(mode))};
  if (wireframe) {
    spec.geometry = "patch_wire.geom";
    spec.defines.push_back("WIREFRAME");
  }
  return spec;
}

std::string surfaceProgramName(ShadingParams::Mode mode, bool wireframe) {
  return std::string("patch_mode") + std::to_string(static_cast<int>(mode)) +
         (wireframe ? "_wire" : "");
}

ProgramSpec probeSpec() {
  ProgramSpec spec;
  spec.vertex = "patch.vert";
  spec.tessControl = "patch.tesc";
  spec.tessEval = "patch.tese";
  spec.defines = {"PROBE"};
  spec.feedbackVaryings = {"probe_uvKH", "probe_positionPatch"};
  return spec;
}

ProgramSpec boundarySpec() {
  ProgramSpec spec;
  spec.vertex = "patch.vert";
  spec.tessControl = "patch_boundary.tesc";
  spec.tessEval = "patch_boundary.tese";
  spec.fragment = "patch_boundary.frag";
  return spec;
}

ProgramSpec overlaySpec() {
  ProgramSpec spec;
  spec.vertex = "overlay.vert";
  spec.fragment = "overlay.frag";
  return spec;
}

// Mesa's draw module (llvmpipe, softpipe) numbers the tessellated vertices of one draw with 16
// bits: a draw whose patches yield more than 65535 vertices loses or scrambles whole patches (seen
// as wedges missing in close-ups). Patches are therefore drawn in runs that stay below that even
// when every edge reaches `maxLevel` ((level + 1)^2 vertices a quad patch); one glMultiDrawArrays
// call, so GPUs that need no split pay nothing measurable.
constexpr int kMaxVerticesPerDraw = 65535;

int patchesPerRun(int maxLevel) {
  const int perPatch = (std::clamp(maxLevel, 1, 64) + 1) * (std::clamp(maxLevel, 1, 64) + 1);
  return std::max(1, kMaxVerticesPerDraw / perPatch);
}

void drawPatchRuns(int patchCount, int maxLevel) {
  const int run = patchesPerRun(maxLevel);
  std::vector<GLint> firsts;
  std::vector<GLsizei> counts;
  for (int first = 0; first < patchCount; first += run) {
    firsts.push_back(first * kControlPointsPerPatch);
    counts.push_back(std::min(run, patchCount - first) * kControlPointsPerPatch);
  }
  glMultiDrawArrays(GL_PATCHES, firsts.data(), counts.data(), static_cast<GLsizei>(firsts.size()));
}

// The largest tessellation level patch.tesc can emit with these settings: T-junction edges reach
// 2^6 whatever the adaptive clamp is.
int largestTessLevel(const ShadingParams& shading) {
  return shading.fixedTessLevel > 0 ? std::min(shading.fixedTessLevel, 64) : 64;
}

const char* const kProbeProgram = "patch_probe";
const char* const kBoundaryProgram = "patch_boundary";
const char* const kOverlayProgram = "overlay";

// Uniform setters by name (glProgramUniform: no program binding needed).
void setUniform(GLuint program, const char* name, const glm::mat4& value) {
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, name), 1, GL_FALSE,
                            glm::value_ptr(value));
}
void setUniform(GLuint program, const char* name, const glm::vec4& value) {
  glProgramUniform4fv(program, glGetUniformLocation(program, name), 1, glm::value_ptr(value));
}
void setUniform(GLuint program, const char* name, const glm::vec3& value) {
  glProgramUniform3fv(program, glGetUniformLocation(program, name), 1, glm::value_ptr(value));
}
void setUniform(GLuint program, const char* name, const glm::vec2& value) {
  glProgramUniform2fv(program, glGetUniformLocation(program, name), 1, glm::value_ptr(value));
}
void setUniform(GLuint program, const char* name, float value) {
  glProgramUniform1f(program, glGetUniformLocation(program, name), value);
}
void setUniform(GLuint program, const char* name, int value) {
  glProgramUniform1i(program, glGetUniformLocation(program, name), value);
}

// A unit vector perpendicular to `axis` that is closest to `hint`.
glm::vec3 perpendicularTo(const glm::vec3& axis, const glm::vec3& hint) {
  glm::vec3 p = hint - glm::dot(hint, axis) * axis;
  if (glm::dot(p, p) < 1e-8f) {
    p = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    p -= glm::dot(p, axis) * axis;
  }
  return glm::normalize(p);
}

// Colour-map stops shared by colorMapCpu (mirror of shaders/common/colormap.glsl).
glm::vec3 fiveStops(float t, const glm::vec3 (&c)[5]) {
  const float x = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const int k = std::min(static_cast<int>(x), 3);
  return glm::mix(c[k], c[k + 1], x - static_cast<float>(k));
}

}  // namespace

// [SECTION] Colours

glm::vec3 patchKindColor(PatchKind kind) {
  switch (kind) {
    case PatchKind::Regular: return {0.15f, 0.15f, 0.15f};
    case PatchKind::Boundary: return {0.45f, 0.30f, 0.10f};
    case PatchKind::PolarRing: return {0.10f, 0.35f, 0.85f};
    case PatchKind::PoleCap: return {0.85f, 0.10f, 0.10f};
    case PatchKind::EndCap: return {0.70f, 0.10f, 0.75f};
  }
  return {0.5f, 0.5f, 0.5f};
}

glm::vec3 ringColor(int ring) {
  // A qualitative palette (Tableau 10 subset), cycling.
  static const glm::vec3 palette[8] = {{0.12f, 0.47f, 0.71f}, {1.00f, 0.50f, 0.05f},
                                       {0.17f, 0.63f, 0.17f}, {0.84f, 0.15f, 0.16f},
                                       {0.58f, 0.40f, 0.74f}, {0.55f, 0.34f, 0.29f},
                                       {0.89f, 0.47f, 0.76f}, {0.09f, 0.75f, 0.81f}};
  if (ring < 0) return {0.35f, 0.35f, 0.35f};
  return palette[ring % 8];
}

glm::vec3 colorMapCpu(ShadingParams::ColorMap map, float value, float range, float rangeBelow) {
  const float side = value >= 0.0f || !(rangeBelow > 0.0f) ? range : rangeBelow;
  const float t = std::clamp(value / std::max(side, 1e-30f), -1.0f, 1.0f);
  switch (map) {
    case ShadingParams::ColorMap::CoolWarm: {
      static const glm::vec3 stops[5] = {{0.230f, 0.299f, 0.754f}, {0.552f, 0.690f, 0.996f},
                                         {0.865f, 0.865f, 0.865f}, {0.958f, 0.603f, 0.482f},
                                         {0.706f, 0.016f, 0.150f}};
      return fiveStops(0.5f * (t + 1.0f), stops);
    }
    case ShadingParams::ColorMap::Viridis: {
      static const glm::vec3 stops[5] = {{0.267f, 0.005f, 0.329f}, {0.229f, 0.322f, 0.546f},
                                         {0.128f, 0.567f, 0.551f}, {0.369f, 0.789f, 0.383f},
                                         {0.993f, 0.906f, 0.144f}};
      return fiveStops(0.5f * (t + 1.0f), stops);
    }
    case ShadingParams::ColorMap::Magnitude: {
      static const glm::vec3 stops[5] = {{0.0f, 0.0f, 0.45f}, {0.0f, 0.3f, 1.0f}, {0.0f, 0.9f, 0.9f},
                                         {1.0f, 0.9f, 0.0f}, {0.85f, 0.0f, 0.0f}};
      return fiveStops(std::abs(t), stops);
    }
    case ShadingParams::ColorMap::Paper:
    default: {
      // Hue 240 (blue) at -range, 120 (green) at 0, 0 (red) at +range; full saturation.
      const float hue = (1.0f - t) * 2.0f;
      glm::vec3 rgb;
      const float offsets[3] = {0.0f, 4.0f, 2.0f};
      for (int c = 0; c < 3; ++c)
        rgb[c] = std::clamp(std::abs(std::fmod(hue + offsets[c], 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
      return 0.95f * rgb;
    }
  }
}

// [SECTION] GL state

struct PatchRenderer::Impl {
  std::shared_ptr<ShaderLibrary> shaders;
  GLuint patchVao = 0, patchPositions = 0, patchKindRings = 0;
  double transitionUnitLength = 0.0;  // see transitionUnitLength(): sets the transition density
  GLuint netVao = 0, netBuffer = 0;
  GLuint poleVao = 0, poleBuffer = 0;
  GLuint timerQueries[2] = {0, 0};
  bool timerPending[2] = {false, false};
  int timerIndex = 0;
  GLsizei netVertexCount = 0, poleCount = 0;
  std::vector<Point> netPointsWorld, polesWorld;  // kept to re-centre when patches change

  void uploadOverlay(GLuint vao, GLuint buffer, const std::vector<Point>& points,
                     const glm::vec3& color, const glm::dvec3& center) {
    std::vector<float> data;
    data.reserve(points.size() * 6);
    for (const Point& p : points) {
      const glm::vec3 q(p - center);
      data.insert(data.end(), {q.x, q.y, q.z, color.x, color.y, color.z});
    }
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)),
                 data.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
    glBindVertexArray(0);
  }
};

PatchRenderer::PatchRenderer() : impl_(std::make_unique<Impl>()) {}

PatchRenderer::~PatchRenderer() {
  if (!impl_ || !impl_->patchVao) return;  // never initialised (or no context)
  Impl& g = *impl_;
  glDeleteVertexArrays(1, &g.patchVao);
  glDeleteVertexArrays(1, &g.netVao);
  glDeleteVertexArrays(1, &g.poleVao);
  const GLuint buffers[] = {g.patchPositions, g.patchKindRings, g.netBuffer, g.poleBuffer};
  glDeleteBuffers(4, buffers);
  glDeleteQueries(2, g.timerQueries);
}

bool PatchRenderer::init(std::string* error, std::shared_ptr<ShaderLibrary> shaders) {
  Impl& g = *impl_;
  g.shaders = shaders ? std::move(shaders) : std::make_shared<ShaderLibrary>();
  // Build each program once per library (renderers sharing a library share the programs).
  // Surface variants of other modes are built on first use (see surfaceProgram).
  const std::pair<std::string, ProgramSpec> programs[] = {
      {surfaceProgramName(ShadingParams::Mode::Shaded, false),
       surfaceSpec(ShadingParams::Mode::Shaded, false)},
      {kProbeProgram, probeSpec()},
      {kBoundaryProgram, boundarySpec()},
      {kOverlayProgram, overlaySpec()}};
  bool ok = true;
  for (const auto& [name, spec] : programs)
    if (!g.shaders->program(name)) ok = g.shaders->build(name, spec, error) && ok;
  if (!ok) return false;

  if (!g.patchVao) {
    glGenVertexArrays(1, &g.patchVao);
    glGenBuffers(1, &g.patchPositions);
    glGenBuffers(1, &g.patchKindRings);
    glGenVertexArrays(1, &g.netVao);
    glGenBuffers(1, &g.netBuffer);
    glGenVertexArrays(1, &g.poleVao);
    glGenBuffers(1, &g.poleBuffer);
    glGenQueries(2, g.timerQueries);
  }
  return true;
}

bool PatchRenderer::reloadShaders(std::string* error) { return impl_->shaders->reloadAll(error); }

unsigned PatchRenderer::surfaceProgram(ShadingParams::Mode mode, bool wireframe) {
  ShaderLibrary& library = *impl_->shaders;
  const std::string name = surfaceProgramName(mode, wireframe);
  if (const unsigned program = library.program(name)) return program;
  std::string error;
  if (library.build(name, surfaceSpec(mode, wireframe), &error)) return library.program(name);
  // A broken variant: report once (lastError) and draw with the plain shaded program.
  lastError_ = error;
  return library.program(surfaceProgramName(ShadingParams::Mode::Shaded, false));
}

// [SECTION] Uploads

void PatchRenderer::setPatches(const std::vector<Patch>& patches) {
  Impl& g = *impl_;
  patchCount_ = static_cast<int>(patches.size());

  // Bounding box of the position-valued control points; the centre keeps float precision.
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const Patch& patch : patches)
    for (int k = 0; k < kControlPointsPerPatch; ++k)
      if (isPositionSlot(patch.kind, k)) {
        lo = glm::min(lo, patch.cp[k]);
        hi = glm::max(hi, patch.cp[k]);
      }
  if (patches.empty()) lo = hi = glm::dvec3(0.0);
  boundsMin_ = lo;
  boundsMax_ = hi;
  center_ = 0.5 * (lo + hi);
  radius_ = std::max(0.5 * glm::length(hi - lo), 1e-12);

  std::vector<float> positions;
  std::vector<int32_t> kindRings;
  positions.reserve(patches.size() * kControlPointsPerPatch * 3);
  kindRings.reserve(patches.size() * kControlPointsPerPatch * 2);
  for (const Patch& patch : patches) {
    const int32_t kindLevelJumps = packKindLevelJumps(patch);
    for (int k = 0; k < kControlPointsPerPatch; ++k) {
      const glm::vec3 p(isPositionSlot(patch.kind, k) ? patch.cp[k] - center_ : patch.cp[k]);
      positions.insert(positions.end(), {p.x, p.y, p.z});
      kindRings.insert(kindRings.end(), {kindLevelJumps, patch.ring});
    }
  }
  impl_->transitionUnitLength = transitionUnitLength(patches);

  glBindVertexArray(g.patchVao);
  glBindBuffer(GL_ARRAY_BUFFER, g.patchPositions);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(positions.size() * sizeof(float)),
               positions.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, g.patchKindRings);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(kindRings.size() * sizeof(int32_t)),
               kindRings.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(1);
  glVertexAttribIPointer(1, 2, GL_INT, 0, nullptr);
  glBindVertexArray(0);

  // Overlays are stored relative to the centre too: re-upload them.
  g.uploadOverlay(g.netVao, g.netBuffer, g.netPointsWorld, {0.1f, 0.1f, 0.1f}, center_);
  g.uploadOverlay(g.poleVao, g.poleBuffer, g.polesWorld, {1.0f, 0.85f, 0.1f}, center_);
}

void PatchRenderer::setControlMesh(const PolyMesh& mesh) {
  Impl& g = *impl_;
  g.netPointsWorld.clear();
  g.netPointsWorld.reserve(mesh.faceVerts.size() * 2);
  // Each face's loop as line pairs (shared edges are drawn twice; cheaper than an edge map).
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    const Index* loop = mesh.face(f);
    const Index k = mesh.faceSize(f);
    for (Index e = 0; e < k; ++e) {
      g.netPointsWorld.push_back(mesh.points[loop[e]]);
      g.netPointsWorld.push_back(mesh.points[loop[(e + 1) % k]]);
    }
  }
  g.netVertexCount = static_cast<GLsizei>(g.netPointsWorld.size());
  g.uploadOverlay(g.netVao, g.netBuffer, g.netPointsWorld, {0.1f, 0.1f, 0.1f}, center_);
}

void PatchRenderer::setPoleMarkers(const std::vector<Point>& poles) {
  Impl& g = *impl_;
  g.polesWorld = poles;
  g.poleCount = static_cast<GLsizei>(poles.size());
  g.uploadOverlay(g.poleVao, g.poleBuffer, g.polesWorld, {1.0f, 0.85f, 0.1f}, center_);
}

// [SECTION] Drawing

glm::mat4 PatchRenderer::modelViewProjection(const ViewParams& view) const {
  // Model matrix = translation to the centre, composed in double to keep precision.
  const glm::dmat4 model = glm::translate(glm::dmat4(1.0), center_);
  return glm::mat4(glm::dmat4(view.proj) * glm::dmat4(view.view) * model);
}

void PatchRenderer::setTessellationUniforms(unsigned program, const ViewParams& view,
                                            const ShadingParams& shading) const {
  setUniform(program, "u_modelViewProjection", modelViewProjection(view));
  setUniform(program, "u_viewportSize", glm::vec2(view.viewport.z, view.viewport.w));
  setUniform(program, "u_tessPixels", std::max(shading.tessPixels, 0.5f));
  setUniform(program, "u_maxTessLevel", static_cast<float>(std::clamp(shading.maxTessLevel, 1, 64)));
  setUniform(program, "u_fixedTessLevel", static_cast<float>(std::min(shading.fixedTessLevel, 64)));
  setUniform(program, "u_transitionDensity", transitionDensity(view, shading));
}

int PatchRenderer::transitionDensity(const ViewParams& view, const ShadingParams& shading) const {
  const double unitLength = impl_->transitionUnitLength;
  if (!(unitLength > 0.0)) return 0;
  // Pixels per world unit at the model centre: proj[1][1] maps view-space y to clip y; / w.
  const glm::dvec4 clip = glm::dmat4(view.proj) * glm::dmat4(view.view) * glm::dvec4(center_, 1.0);
  const double pixelsPerUnit = 0.5 * view.viewport.w * double(view.proj[1][1]) / std::max(clip.w, 1e-9);
  const double segments = unitLength * pixelsPerUnit / std::max(double(shading.tessPixels), 0.5);
  return static_cast<int>(std::clamp(std::lround(std::log2(std::max(segments, 1e-30))), -64L, 64L));
}

void PatchRenderer::draw(const ViewParams& view, const ShadingParams& shading,
                         const DisplayFlags& flags) {
  Impl& g = *impl_;
  glViewport(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.w);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);  // two-sided surfaces
  glDisable(GL_BLEND);

  const glm::mat4 mvp = modelViewProjection(view);
  const glm::vec3 eye(glm::dvec3(view.eye) - center_);

  // GPU time of the previous use of this query slot (non-blocking when available).
  const int slot = g.timerIndex;
  if (g.timerPending[slot]) {
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(g.timerQueries[slot], GL_QUERY_RESULT, &nanoseconds);
    stats_.gpuMilliseconds = static_cast<double>(nanoseconds) * 1e-6;
  }
  glBeginQuery(GL_TIME_ELAPSED, g.timerQueries[slot]);
  g.timerPending[slot] = true;
  g.timerIndex = 1 - slot;
  stats_.patchCount = patchCount_;

  const GLsizei patchVertices = patchCount_ * kControlPointsPerPatch;
  if (patchCount_ > 0 && (flags.surface || flags.wireframe)) {
    const GLuint program = surfaceProgram(shading.mode, flags.wireframe);
    // Light lines: direction B, across E = W x B, plane normal W = B x E (SCHEMES.md section 7).
    const glm::vec3 B = glm::normalize(shading.highlightDir);
    const glm::vec3 W = perpendicularTo(B, shading.highlightPlaneNormal);
    const glm::vec3 E = glm::cross(W, B);
    const float radius = static_cast<float>(radius_);
    // Key light fixed in view space (upper left, in front), expressed in world axes.
    const glm::vec3 keyView = glm::length(shading.keyLightView) > 1e-6f ? glm::normalize(shading.keyLightView)
                                                                         : glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 keyWorld = glm::normalize(glm::transpose(glm::mat3(view.view)) * keyView);

    setTessellationUniforms(program, view, shading);
    setUniform(program, "u_colormap", static_cast<int>(shading.colormap));
    setUniform(program, "u_range", shading.range);
    setUniform(program, "u_rangeBelow", shading.rangeBelow > 0.0f ? shading.rangeBelow : shading.range);
    setUniform(program, "u_curvatureLighting", shading.curvatureLighting);
    setUniform(program, "u_eye", eye);
    setUniform(program, "u_keyLight", keyWorld);
    setUniform(program, "u_surfaceColor", shading.surfaceColor);
    setUniform(program, "u_lineDirection", B);
    setUniform(program, "u_lineAcross", E);
    setUniform(program, "u_planeNormal", W);
    setUniform(program, "u_planePoint", W * (2.0f * radius));
    setUniform(program, "u_lineSpacing",
               shading.mode == ShadingParams::Mode::Reflection
                   ? std::max(shading.reflectionSpacing, 1e-4f)
                   : std::max(shading.highlightSpacing * radius, 1e-12f));
    setUniform(program, "u_lineWidth", std::clamp(shading.highlightWidth, 0.0f, 1.0f));
    setUniform(program, "u_drawSurface", flags.surface ? 1 : 0);
    setUniform(program, "u_wireColor", glm::vec3(0.05f, 0.05f, 0.08f));

    glUseProgram(program);
    glBindVertexArray(g.patchVao);
    glPatchParameteri(GL_PATCH_VERTICES, kControlPointsPerPatch);
    // Push the surface back a little so boundary curves and markers on it stay visible.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 2.0f);
    drawPatchRuns(patchCount_, largestTessLevel(shading));
    glDisable(GL_POLYGON_OFFSET_FILL);
  }

  if (patchCount_ > 0 && flags.patchBoundaries) {
    const GLuint program = g.shaders->program(kBoundaryProgram);
    setUniform(program, "u_modelViewProjection", mvp);
    setUniform(program, "u_boundarySegments", 16.0f);
    setUniform(program, "u_colorByRing", flags.boundaryColor == DisplayFlags::BoundaryColor::Ring);
    glm::vec3 kindColors[5], ringColors[8];
    for (int k = 0; k < 5; ++k) kindColors[k] = patchKindColor(static_cast<PatchKind>(k));
    for (int k = 0; k < 8; ++k) ringColors[k] = ringColor(k);
    glProgramUniform3fv(program, glGetUniformLocation(program, "u_kindColors"), 5,
                        glm::value_ptr(kindColors[0]));
    glProgramUniform3fv(program, glGetUniformLocation(program, "u_ringColors"), 8,
                        glm::value_ptr(ringColors[0]));
    setUniform(program, "u_noRingColor", ringColor(-1));
    glUseProgram(program);
    glBindVertexArray(g.patchVao);
    glPatchParameteri(GL_PATCH_VERTICES, kControlPointsPerPatch);
    glDrawArrays(GL_PATCHES, 0, patchVertices);
  }

  const GLuint overlay = g.shaders->program(kOverlayProgram);
  setUniform(overlay, "u_modelViewProjection", mvp);
  setUniform(overlay, "u_alpha", 1.0f);
  setUniform(overlay, "u_colorOverride", glm::vec4(0.0f));
  if (flags.controlNet && g.netVertexCount > 0) {
    // Dark lines over the surface, light ones over the background when the surface is hidden (the
    // dark net vanished against the dark background). With the surface shown, the parts of the net
    // behind it are drawn faintly first, so the net reads as one piece, as CAD viewers show hidden lines.
    const glm::vec3 netColour = flags.surface ? glm::vec3(0.06f, 0.06f, 0.08f) : glm::vec3(0.85f, 0.87f, 0.9f);
    setUniform(overlay, "u_roundPoints", 0);
    setUniform(overlay, "u_pointSize", 1.0f);
    setUniform(overlay, "u_colorOverride", glm::vec4(netColour, 1.0f));
    glUseProgram(overlay);
    glBindVertexArray(g.netVao);
    if (flags.surface) {
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keeps the image's alpha
      glDepthMask(GL_FALSE);
      glDepthFunc(GL_GREATER);
      setUniform(overlay, "u_depthBias", 0.0f);
      setUniform(overlay, "u_alpha", 0.3f);
      glDrawArrays(GL_LINES, 0, g.netVertexCount);
      glDepthFunc(GL_LEQUAL);
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
      setUniform(overlay, "u_alpha", 1.0f);
    }
    // Where the net meets the surface (boundaries, poles) a small bias keeps it in front.
    setUniform(overlay, "u_depthBias", 0.0005f);
    glDrawArrays(GL_LINES, 0, g.netVertexCount);
    setUniform(overlay, "u_colorOverride", glm::vec4(0.0f));
  }
  if (flags.poleMarkers && g.poleCount > 0) {
    setUniform(overlay, "u_depthBias", 0.002f);
    setUniform(overlay, "u_roundPoints", 1);
    setUniform(overlay, "u_pointSize", 11.0f);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(overlay);
    glBindVertexArray(g.poleVao);
    glDrawArrays(GL_POINTS, 0, g.poleCount);
    glDisable(GL_PROGRAM_POINT_SIZE);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  glEndQuery(GL_TIME_ELAPSED);
}

// [SECTION] Probe (transform feedback)

std::vector<SurfaceProbe> PatchRenderer::probeSurface(int tessLevel) {
  ShadingParams shading;
  shading.fixedTessLevel = std::clamp(tessLevel, 1, 64);
  return probeSurface(ViewParams{}, shading);
}

std::vector<SurfaceProbe> PatchRenderer::probeSurface(const ViewParams& view,
                                                      const ShadingParams& shading) {
  Impl& g = *impl_;
  std::vector<SurfaceProbe> samples;
  if (patchCount_ == 0) return samples;
  const GLuint program = g.shaders->program(kProbeProgram);
  setTessellationUniforms(program, view, shading);
  // The buffer must hold the most vertices any patch can produce.
  const int tessLevel = shading.fixedTessLevel > 0 ? std::min(shading.fixedTessLevel, 64)
                                                   : std::clamp(shading.maxTessLevel, 1, 64);

  // At most (level+1)^2 points per patch; 8 floats each.
  const size_t capacity = size_t(patchCount_) * (tessLevel + 1) * (tessLevel + 1);
  GLuint buffer = 0, query = 0;
  glGenBuffers(1, &buffer);
  glGenQueries(1, &query);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffer);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(capacity * 8 * sizeof(float)),
               nullptr, GL_STATIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);

  glUseProgram(program);
  glBindVertexArray(g.patchVao);
  glPatchParameteri(GL_PATCH_VERTICES, kControlPointsPerPatch);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
  glBeginTransformFeedback(GL_POINTS);
  drawPatchRuns(patchCount_, largestTessLevel(shading));
  glEndTransformFeedback();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  glDisable(GL_RASTERIZER_DISCARD);
  GLuint written = 0;
  glGetQueryObjectuiv(query, GL_QUERY_RESULT, &written);

  std::vector<float> data(size_t(written) * 8);
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0,
                     static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glDeleteBuffers(1, &buffer);
  glDeleteQueries(1, &query);
  glBindVertexArray(0);
  glUseProgram(0);

  samples.resize(written);
  for (size_t k = 0; k < samples.size(); ++k) {
    const float* d = data.data() + 8 * k;
    SurfaceProbe& s = samples[k];
    s.u = d[0];
    s.v = d[1];
    s.gaussian = d[2];
    s.mean = d[3];
    s.position = glm::dvec3(d[4], d[5], d[6]) + center_;
    s.patch = static_cast<int>(d[7]);
  }
  return samples;
}

}  // namespace polarview
