// PatchRenderer: GPU tessellation of bicubic patches with curvature / highlight shading and
// overlays (see patch_renderer.h). Shaders: shaders/patch.*, patch_boundary.*, overlay.*.
#include "render/patch_renderer.h"

#include "core/mesh/constants.h"
#include "core/subdiv/parallel_for.h"

#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "render/shader_library.h"

namespace polarview {
namespace {

constexpr int kControlPointsPerPatch = 16;
// Per control point: GPU form, world hi, world lo; per patch: its frame's texels.
constexpr size_t kFloatsPerPoint = 9;
constexpr size_t kFloatsPerPatch = kControlPointsPerPatch * kFloatsPerPoint;

// [SECTION] Precision: each patch in its own frame, as differences
//
// Deep levels (RTS/BPS reach 24 on a globe, the innermost ring ~2^-L of the model; C2PS reaches 12
// with ring patches 1.5e4 times longer than wide) are beyond what float world coordinates resolve:
// at level 20 a ring of 1e-6 is a few float steps wide (6e-8 near 1), its curvature (heights of
// ~1e-12 over it) is gone, and a camera 1e-6 away cannot be placed. So the GPU gets each patch in a
// form computed here in double:
//  - in its own frame: origin at the patch, z along its normal, so coordinates keep float's 24 bits
//    relative to the patch's size and the heights above the tangent plane, which curvature comes
//    from, keep them relative to themselves;
//  - as forward differences: B-spline control points c_0..c_3 along a direction become
//    (c_0, D c_0, D^2 c_0, D^3 c_0) (a table D_u^a D_v^b c_00 for a patch, shaders/common/
//    patch_eval.glsl evaluates it in the matching basis), so a second derivative is made of second
//    and third differences only, each rounded to float relative to itself. Taking them on the GPU
//    from rounded points instead cancels: across a deep C2PS ring the second difference is ~1e-4
//    of the points' spread in the frame (1e-8 of it in world axes), below float's 6e-8;
//  - a pole cap's angle measured from its sector's start (tau0 = 0; p1, p2 and p4, p5 turned to
//    match), so that a sector of 2^-17 turns (C2PS level 12) is not rounded against a whole turn.
// The origin goes to the GPU as a double split into float hi + lo, from which common/patch_frame.glsl
// subtracts the eye's hi and lo: positions relative to the eye, precise to a float of their own
// size, projected by the view's rotation only. The control points go up the same way, shared by
// the patches that share them: tessellation levels and the positions of B-spline patches come from
// those (so both sides of an edge get the same levels and place it alike); normals, K and H from
// the frame.

constexpr int kFrameTexelsPerPatch = 5;  // origin hi, origin lo, axes x, y, z (patch_frame.glsl)
constexpr size_t kFloatsPerFrame = 3 * kFrameTexelsPerPatch;
constexpr int kFrameTextureUnit = 3;     // texture units of u_patchFrames and u_patchKinds
constexpr int kKindTextureUnit = 4;
constexpr int kPointTextureUnit = 5;     // u_patchPoints, u_drawItems, u_rowSlots
constexpr int kItemTextureUnit = 6;
constexpr int kRowSlotTextureUnit = 7;

// A double vector rounded to float. Through a volatile: GCC 12.2 at -O2 and -O3 vectorises
// double(float(x)) back to x (seen: the lo of splitHiLo came out 0 in y and z, a level-20 cap
// then sat 3e-8 off its ring).
glm::vec3 roundToFloat(const glm::dvec3& value) {
  glm::vec3 rounded;
  for (int c = 0; c < 3; ++c) {
    volatile float component = static_cast<float>(value[c]);
    rounded[c] = component;
  }
  return rounded;
}

// A double as the nearest finite float (a colour range beyond float's range saturates as it would).
float floatInRange(double value) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return std::isnan(value) ? 0.0f : float(std::clamp(value, -kMax, kMax));
}

bool isPerspective(const ViewParams& view) { return view.proj[2][3] < -0.5; }

// A double vector as float hi + lo: hi + lo = value to ~2^-48 of it.
void splitHiLo(const glm::dvec3& value, float* hi, float* lo) {
  const glm::vec3 rounded = roundToFloat(value);
  const glm::vec3 rest(value - glm::dvec3(rounded));
  for (int c = 0; c < 3; ++c) {
    hi[c] = rounded[c];
    lo[c] = rest[c];
  }
}

// A patch's frame: world = origin + axes * local. axes is a rotation rounded to float (what the GPU
// uses); toLocal is its inverse in double, so that round trips are exact to double precision.
struct PatchFrameCpu {
  glm::dvec3 origin{0.0};
  glm::mat3 axes{1.0f};
  glm::dmat3 toLocal{1.0};
};

// Frame with z along `normal` and x along `tangent` (projected); axis-aligned fallbacks where
// either is degenerate.
PatchFrameCpu frameAt(const glm::dvec3& origin, const glm::dvec3& tangent, const glm::dvec3& normal) {
  PatchFrameCpu frame;
  frame.origin = origin;
  // Directions only: first scaled to a largest component of 1, so that the squares in their lengths
  // neither underflow (a model of 1e-80 has normals du x dv of 1e-160) nor overflow.
  const auto direction = [](const glm::dvec3& v) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return largest > 0.0 && std::isfinite(largest) ? v / largest : glm::dvec3(0.0);
  };
  const glm::dvec3 scaledNormal = direction(normal), scaledTangent = direction(tangent);
  const double normalLength = glm::length(scaledNormal);
  const glm::dvec3 z = normalLength > 0.0 ? scaledNormal / normalLength : glm::dvec3(0, 0, 1);
  glm::dvec3 x = scaledTangent - glm::dot(scaledTangent, z) * z;
  if (!(glm::length(x) > 1e-6 * glm::length(scaledTangent)) || !std::isfinite(glm::length(x))) {
    x = std::abs(z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    x -= glm::dot(x, z) * z;
  }
  x = glm::normalize(x);
  const glm::dvec3 y = glm::cross(z, x);  // right-handed: x cross y = z
  frame.axes = glm::mat3(roundToFloat(x), roundToFloat(y), roundToFloat(z));
  frame.toLocal = glm::inverse(glm::dmat3(frame.axes));
  return frame;
}

// (c0, c1, c2, c3) -> (c0, D c0, D^2 c0, D^3 c0), in place, for entries first, first + stride, ...
template <size_t N>
void toForwardDifferences(std::array<glm::dvec3, N>& c, int first, int stride) {
  glm::dvec3& c0 = c[first];
  glm::dvec3& c1 = c[first + stride];
  glm::dvec3& c2 = c[first + 2 * stride];
  glm::dvec3& c3 = c[first + 3 * stride];
  const glm::dvec3 d3 = ((c3 - c0) - 3.0 * (c2 - c1)), d2 = ((c2 - c1) - (c1 - c0)), d1 = c1 - c0;
  c1 = d1;
  c2 = d2;
  c3 = d3;
}

// What a cap's non-position slot holds beside its GPU form (patch.vert passes it on as it is, not
// relative to the eye): p1..p5 and e_j as world vectors, slot 10 (j, n, R) for sector j of n.
// Neighbouring sectors place their shared radial edge from these and the shared world points in the
// same operations (patch.tese, capPositionFromEye), so the edge is the same bits on both sides;
// each sector's rotated frame alone left pinholes between 49,152 sub-pixel sectors (C2PS level 12).
glm::dvec3 capSharedSlot(const Patch& patch, int k) {
  if (patch.kind != PatchKind::PoleCap) return glm::dvec3(0.0);
  if (k == 10) return glm::dvec3(patch.sector, patch.sectorCount, kPoleCapRadius);
  if (k == 11) return glm::dvec3(0.0);
  return patch.cp[k];
}

// `value` of control slot k in GPU units: lengths times `perUnit` (a power of two, so exact); a
// cap's slot 10 (tau, n, R: R in the cap's own radial unit) as it is.
glm::dvec3 inUnits(PatchKind kind, int k, const glm::dvec3& value, double perUnit) {
  return kind == PatchKind::PoleCap && k == 10 ? value : value * perUnit;
}

// A patch as the GPU evaluates it (see the section's top), with its frame. A cap's f_{j-1..j+2}
// (patch.h) go up in the lo texels of its vector slots (patch_frame.glsl, fetchCapSecond):
// capSecond in the GPU form, capSecondWorld as world vectors.
struct GpuPatch {
  PatchFrameCpu frame;
  std::array<glm::dvec3, 16> cp{};
  std::array<glm::dvec3, 4> capSecond{}, capSecondWorld{};
};

// A ring patch goes up turned by its ringTurn (u outwards, v around: sector groups, patch.tese; its
// jumps with it, packKindLevelJumps): control point k of the GPU form is the patch's
// turnedControlIndex(k, ringTurn).
const glm::dvec3& drawnPoint(const Patch& patch, int k) { return patch.cp[size_t(turnedControlIndex(k, patch.ringTurn))]; }

GpuPatch gpuForm(const Patch& patch) {
  GpuPatch out;
  if (patch.kind == PatchKind::PoleCap) {
    // The sector's start angle theta0 moves into the coefficients: T's terms in (x, y) are
    // p1 cos + p2 sin (turned by theta0) and p4 cos 2 + p5 sin 2 (turned by 2 theta0).
    const double n = double(patch.sectorCount), theta0 = kTwoPi * (double(patch.sector) / n);
    const double c1 = std::cos(theta0), s1 = std::sin(theta0), c2 = std::cos(2.0 * theta0), s2 = std::sin(2.0 * theta0);
    std::array<glm::dvec3, 16> cp = patch.cp;
    cp[1] = c1 * patch.cp[1] + s1 * patch.cp[2];
    cp[2] = -s1 * patch.cp[1] + c1 * patch.cp[2];
    cp[4] = c2 * patch.cp[4] + s2 * patch.cp[5];
    cp[5] = -s2 * patch.cp[4] + c2 * patch.cp[5];
    out.frame = frameAt(cp[0], cp[1], glm::cross(cp[1], cp[2]));
    const PatchFrameCpu& f = out.frame;
    out.cp[0] = glm::dvec3(0.0);  // p0 is the origin
    for (int k = 1; k <= 5; ++k) out.cp[k] = f.toLocal * cp[k];
    for (int k = 6; k <= 9; ++k) out.cp[k] = f.toLocal * (cp[k] - f.origin);
    out.cp[10] = glm::dvec3(0.0, 1.0 / n, kPoleCapRadius);
    out.cp[11] = glm::dvec3(0.0);
    for (int k = 12; k <= 15; ++k) out.cp[k] = f.toLocal * cp[k];
    for (int k = 0; k < 4; ++k) {
      out.capSecondWorld[size_t(k)] = capSecondPoint(patch, k);
      out.capSecond[size_t(k)] = f.toLocal * capSecondPoint(patch, k);
    }
    toForwardDifferences(out.cp, 6, 1);   // boundary curve b_{j-1..j+2}
    toForwardDifferences(out.cp, 12, 1);  // first radial derivative e_{j-1..j+2}
    toForwardDifferences(out.capSecond, 0, 1);  // second radial derivative f_{j-1..j+2}
    out.frame.origin += patch.origin;     // the frame sat at p0 relative to the patch's origin
    return out;
  }
  // B-spline patch: frame at the centre of the parameter square (limit point, du, du x dv; the
  // uniform cubic basis at 1/2 is (1, 23, 23, 1) / 48, its derivative (-1, -5, 5, 1) / 8); a patch
  // that is not finite there keeps world axes at its cp[5].
  static constexpr double kB[4] = {1.0 / 48, 23.0 / 48, 23.0 / 48, 1.0 / 48}, kD[4] = {-0.125, -0.625, 0.625, 0.125};
  glm::dvec3 centre(0.0), du(0.0), dv(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const glm::dvec3& c = drawnPoint(patch, 4 * j + i);
      centre += (kB[i] * kB[j]) * c;
      du += (kD[i] * kB[j]) * c;
      dv += (kB[i] * kD[j]) * c;
    }
  if (std::isfinite(glm::dot(centre, centre) + glm::dot(du, du) + glm::dot(dv, dv)))
    out.frame = frameAt(centre, du, glm::cross(du, dv));
  else
    out.frame = frameAt(drawnPoint(patch, 5), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1));
  for (int k = 0; k < 16; ++k) out.cp[k] = out.frame.toLocal * (drawnPoint(patch, k) - out.frame.origin);
  for (int j = 0; j < 4; ++j) toForwardDifferences(out.cp, 4 * j, 1);  // along u, each row
  for (int i = 0; i < 4; ++i) toForwardDifferences(out.cp, i, 4);      // then along v
  out.frame.origin += patch.origin;  // the frame was placed relative to the patch's origin
  return out;
}


// The per-patch kind texel's x as patch.tesc unpacks it: bits 0-7 PatchKind, 8-15 level, then
// Patch::edgeLevelDelta of edges 0..3 as signed 4-bit fields at bits 16 + 4s (jumps beyond
// [-8, 7] get the same tessellation as those ends, see transitionEdgeSegments).
// A ring patch's jumps go up turned with it (gpuForm).
int32_t packKindLevelJumps(const Patch& patch) {
  uint32_t packed = uint32_t(patch.kind) | uint32_t(patch.level) << 8;
  for (int s = 0; s < 4; ++s)
    packed |= (uint32_t(std::clamp(int(patch.edgeLevelDelta[size_t((s + patch.ringTurn) % 4)]), -8, 7)) & 0xFu) << (16 + 4 * s);
  return static_cast<int32_t>(packed);
}

// The transition unit length: the world length of one level-0 parameter unit along the T-junction
// edges, the mean of chord * 2^level (chord between the face's corner control points) over the
// coarse sides of the coarsest level that has any; 0 if none. The coarsest only: a set cut at a
// shallower level (PatchRenderer's caller drawing fewer levels where deeper rings are below a
// pixel) then gets the same tessellation as the full one. One chunk of patches' part.
struct TransitionSides {
  int level = std::numeric_limits<int>::max();
  double sum = 0.0;
  size_t sides = 0;
  void add(int sideLevel, double length, size_t count) {
    if (sideLevel > level || count == 0) return;
    if (sideLevel < level) level = sideLevel, sum = 0.0, sides = 0;
    sum += length;
    sides += count;
  }
};

void addTransitionSides(const Patch& patch, TransitionSides& found) {
  static constexpr int kEdgeCorners[4][2] = {{5, 6}, {6, 10}, {10, 9}, {9, 5}};  // patch.h order
  if (patch.kind == PatchKind::PoleCap) return;
  for (int s = 0; s < 4; ++s)
    if (patch.edgeLevelDelta[s] > 0)
      found.add(patch.level, std::ldexp(glm::length(patch.cp[kEdgeCorners[s][0]] - patch.cp[kEdgeCorners[s][1]]), patch.level), 1);
}

// Program specs: every shader file and variant the renderer uses.
// One surface program per shading mode (a #define, so llvmpipe runs no per-pixel mode branches),
// with or without the wireframe geometry shader, and for lone patches or for groups of ring
// sectors (SECTOR_GROUPS: patch.tese's path for them, which slows llvmpipe's shader for all).
ProgramSpec surfaceSpec(ShadingParams::Mode mode, bool wireframe, bool groups) {
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
  if (groups) spec.defines.push_back("SECTOR_GROUPS");
  return spec;
}

std::string surfaceProgramName(ShadingParams::Mode mode, bool wireframe, bool groups) {
  return std::string("patch_mode") + std::to_string(static_cast<int>(mode)) + (wireframe ? "_wire" : "") +
         (groups ? "_groups" : "");
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

// Draws the patches in `ranges` of slots, in runs of at most patchesPerRun(maxLevel) patches.
void drawPatchRuns(const std::vector<PatchRenderer::DrawRange>& ranges, int maxLevel) {
  const size_t run = size_t(patchesPerRun(maxLevel));
  std::vector<GLint> firsts;
  std::vector<GLsizei> counts;
  for (const PatchRenderer::DrawRange& range : ranges)
    for (size_t first = 0; first < range.count; first += run) {
      firsts.push_back(static_cast<GLint>((range.firstSlot + first) * kControlPointsPerPatch));
      counts.push_back(static_cast<GLsizei>(std::min(run, range.count - first) * kControlPointsPerPatch));
    }
  if (!firsts.empty()) glMultiDrawArrays(GL_PATCHES, firsts.data(), counts.data(), static_cast<GLsizei>(firsts.size()));
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

}  // namespace

// [SECTION] GL state

struct PatchRenderer::Impl {
  std::shared_ptr<ShaderLibrary> shaders;
  // Per control point (patch.vert): its GPU form, world hi, world lo (interleaved).
  GLuint patchVao = 0, patchPositions = 0;
  // Per patch (patch_frame.glsl's texels): frame; kind, level, jumps and ring.
  GLuint frameBuffer = 0, frameTexture = 0, kindBuffer = 0, kindTexture = 0;
  size_t positionsCapacity = 0, frameCapacity = 0, kindCapacity = 0;  // bytes allocated in each
  // The control points again as texels (patch.tese fetches a group's other sectors); per drawn item
  // its texel; per row its slots; the drawn items' indices.
  GLuint pointTexture = 0, itemBuffer = 0, itemTexture = 0, rowSlotBuffer = 0, rowSlotTexture = 0;
  double transitionUnitLength = 0.0;  // see addTransitionSides: sets the transition density
  GLuint netVao = 0, netBuffer = 0;
  GLuint poleVao = 0, poleBuffer = 0;
  GLuint timerQueries[2] = {0, 0};
  bool timerPending[2] = {false, false};
  int timerIndex = 0;
  GLsizei netVertexCount = 0, poleCount = 0;
  std::vector<Point> netPointsWorld, polesWorld;  // kept to re-centre when patches change
  std::vector<glm::vec3> netColors;              // per net point (crease edges stand out)

  // Overlay vertices (overlay.vert): position hi, lo (relative to the centre, in GPU units), colour.
  // Points the patch VAO and the texture buffers at the current buffers (after they were made or
  // grown).
  void attachBuffers() {
    glBindVertexArray(patchVao);
    glBindBuffer(GL_ARRAY_BUFFER, patchPositions);
    // Locations 0 GPU form, 2 world hi, 3 world lo, at floats 0, 3, 6 of 9.
    for (const auto& [location, offset] : {std::pair<GLuint, size_t>{0, 0}, {2, 3}, {3, 6}}) {
      glEnableVertexAttribArray(location);
      glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 9 * sizeof(float), reinterpret_cast<void*>(offset * sizeof(float)));
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindTexture(GL_TEXTURE_BUFFER, frameTexture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGB32F, frameBuffer);
    glBindTexture(GL_TEXTURE_BUFFER, kindTexture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RG32I, kindBuffer);
    glBindTexture(GL_TEXTURE_BUFFER, pointTexture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGB32F, patchPositions);
    glBindTexture(GL_TEXTURE_BUFFER, rowSlotTexture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32I, rowSlotBuffer);
    glBindTexture(GL_TEXTURE_BUFFER, itemTexture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32I, itemBuffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
  }
  // `colors`: one per point, or one for all.
  void uploadOverlay(GLuint vao, GLuint buffer, const std::vector<Point>& points,
                     const std::vector<glm::vec3>& colors, const glm::dvec3& center, double unit) {
    std::vector<float> data(points.size() * 9);
    for (size_t k = 0; k < points.size(); ++k) {
      float* vertex = data.data() + 9 * k;
      splitHiLo((points[k] - center) / unit, vertex, vertex + 3);
      const glm::vec3& color = colors[colors.size() == points.size() ? k : 0];
      for (int c = 0; c < 3; ++c) vertex[6 + c] = color[c];
    }
    constexpr GLsizei kStride = 9 * sizeof(float);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)),
                 data.data(), GL_STATIC_DRAW);
    // Attribute location and float offset in the vertex: 0 hi at 0, 2 lo at 3, 1 colour at 6.
    const std::pair<GLuint, size_t> attributes[] = {{0, 0}, {2, 3}, {1, 6}};
    for (const auto& [location, offset] : attributes) {
      glEnableVertexAttribArray(location);
      glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, kStride, reinterpret_cast<void*>(offset * sizeof(float)));
    }
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
  const GLuint buffers[] = {g.patchPositions, g.kindBuffer, g.frameBuffer, g.netBuffer, g.poleBuffer,
                            g.itemBuffer, g.rowSlotBuffer};
  glDeleteBuffers(7, buffers);
  const GLuint textures[] = {g.frameTexture, g.kindTexture, g.pointTexture, g.itemTexture, g.rowSlotTexture};
  glDeleteTextures(5, textures);
  glDeleteQueries(2, g.timerQueries);
}

bool PatchRenderer::init(std::string* error, std::shared_ptr<ShaderLibrary> shaders) {
  Impl& g = *impl_;
  g.shaders = shaders ? std::move(shaders) : std::make_shared<ShaderLibrary>();
  // Build each program once per library (renderers sharing a library share the programs).
  // Surface variants of other modes are built on first use (see surfaceProgram).
  const std::pair<std::string, ProgramSpec> programs[] = {
      {surfaceProgramName(ShadingParams::Mode::Shaded, false, false),
       surfaceSpec(ShadingParams::Mode::Shaded, false, false)},
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
    glGenBuffers(1, &g.kindBuffer);
    glGenBuffers(1, &g.frameBuffer);
    glGenTextures(1, &g.frameTexture);
    glGenTextures(1, &g.kindTexture);
    glGenTextures(1, &g.pointTexture);
    glGenTextures(1, &g.itemTexture);
    glGenTextures(1, &g.rowSlotTexture);
    glGenBuffers(1, &g.itemBuffer);
    glGenBuffers(1, &g.rowSlotBuffer);
    // Texture buffers need a store before they are attached.
    for (const GLuint buffer : {g.itemBuffer, g.rowSlotBuffer}) {
      glBindBuffer(GL_TEXTURE_BUFFER, buffer);
      glBufferData(GL_TEXTURE_BUFFER, 16, nullptr, GL_DYNAMIC_DRAW);
    }
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    glGenVertexArrays(1, &g.netVao);
    glGenBuffers(1, &g.netBuffer);
    glGenVertexArrays(1, &g.poleVao);
    glGenBuffers(1, &g.poleBuffer);
    glGenQueries(2, g.timerQueries);
  }
  return true;
}

bool PatchRenderer::reloadShaders(std::string* error) { return impl_->shaders->reloadAll(error); }

unsigned PatchRenderer::surfaceProgram(ShadingParams::Mode mode, bool wireframe, bool groups) {
  ShaderLibrary& library = *impl_->shaders;
  const std::string name = surfaceProgramName(mode, wireframe, groups);
  if (const unsigned program = library.program(name)) return program;
  std::string error;
  if (library.build(name, surfaceSpec(mode, wireframe, groups), &error)) return library.program(name);
  // A broken variant: report once (lastError) and draw with the plain shaded program.
  lastError_ = error;
  return library.program(surfaceProgramName(ShadingParams::Mode::Shaded, false, groups));
}

// [SECTION] Uploads

namespace {

// Makes `buffer` hold at least `bytes` (capacity `*capacity`), keeping its first `keepBytes`:
// a grown buffer is a new one with the kept part copied on the GPU (glCopyBufferSubData); one far
// larger than needed with nothing kept is given back. Returns the buffer to use.
GLuint reserveBuffer(GLuint buffer, size_t* capacity, size_t keepBytes, size_t bytes) {
  if (bytes <= *capacity && !(keepBytes == 0 && bytes < *capacity / 4)) return buffer;
  GLuint grown = 0;
  glGenBuffers(1, &grown);
  const size_t wanted = keepBytes > 0 ? bytes + bytes / 4 : bytes;  // stepping deeper: room for the next level
  glBindBuffer(GL_COPY_WRITE_BUFFER, grown);
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(wanted), nullptr, GL_STATIC_DRAW);
  if (keepBytes > 0) {
    glBindBuffer(GL_COPY_READ_BUFFER, buffer);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, static_cast<GLsizeiptr>(keepBytes));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
  }
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  glDeleteBuffers(1, &buffer);
  *capacity = wanted;
  return grown;
}

// Writes `count` elements of `size` bytes from `data` at element `first` of `buffer`.
void writeBuffer(GLenum target, GLuint buffer, size_t first, size_t count, size_t size, const void* data) {
  if (count == 0) return;
  glBindBuffer(target, buffer);
  glBufferSubData(target, static_cast<GLintptr>(first * size), static_cast<GLsizeiptr>(count * size), data);
  glBindBuffer(target, 0);
}

// Where a set of patches goes in the GPU's slots: the stable sequence from slot 0 (slots uploaded
// under the same stamp stay valid, also past this set's part of it), then the rest of the set after
// every valid slot.
struct SlotLayout {
  size_t stableCount = 0;   // the set's patches of the stable sequence
  bool sameSequence = false;  // the sequence on the GPU is this one
  size_t validBefore = 0;   // its slots on the GPU that stay valid
  size_t reused = 0;        // the set's patches already on the GPU (not packed again)
  size_t stableSlots = 0;   // slots of the stable sequence after this upload
  size_t tailCount = 0;     // the set's other patches, after stableSlots
  size_t totalSlots = 0;

  size_t slotOf(size_t p) const { return p < stableCount ? p : stableSlots + (p - stableCount); }
};

SlotLayout layoutSlots(size_t patchCount, uint64_t stableStamp, size_t stableCount, uint64_t stampOnGpu,
                       size_t stableOnGpu) {
  SlotLayout layout;
  layout.stableCount = stableStamp != 0 ? std::min(stableCount, patchCount) : 0;
  layout.sameSequence = stableStamp != 0 && stableStamp == stampOnGpu;
  layout.validBefore = layout.sameSequence ? stableOnGpu : 0;
  layout.reused = std::min(layout.validBefore, layout.stableCount);
  layout.stableSlots = std::max(layout.validBefore, layout.stableCount);
  layout.tailCount = patchCount - layout.stableCount;
  layout.totalSlots = layout.stableSlots + layout.tailCount;
  return layout;
}

// Kinds and level jumps by slot (the jumps change with the level: all of them) into `kindRings`
// (two ints a slot), and the transition unit length (addTransitionSides), in one pass over all
// patches split over the cores: fixed chunks summed in order, so the sum does not depend on the
// number of threads.
double packKindsAndTransitions(const std::vector<Patch>& patches, const SlotLayout& layout,
                               std::vector<int32_t>& kindRings) {
  kindRings.assign(layout.totalSlots * 2, 0);
  constexpr size_t kChunk = 4096;
  const size_t chunks = (patches.size() + kChunk - 1) / kChunk;
  std::vector<TransitionSides> chunkSides(chunks);
  const unsigned scanParts = threadsFor(patches.size() * 4);
  runParts(scanParts, [&](unsigned part) {
    for (size_t c = part; c < chunks; c += scanParts)
      for (size_t p = c * kChunk; p < std::min(patches.size(), (c + 1) * kChunk); ++p) {
        const Patch& patch = patches[p];
        const size_t slot = layout.slotOf(p);
        kindRings[2 * slot] = packKindLevelJumps(patch);
        kindRings[2 * slot + 1] = patch.ring;
        addTransitionSides(patch, chunkSides[c]);
      }
  });
  TransitionSides transitions;
  for (const TransitionSides& part : chunkSides) transitions.add(part.level, part.sum, part.sides);
  return transitions.sides > 0 ? transitions.sum / double(transitions.sides) : 0.0;
}

// Per patch from `first` on: its frame texels; per control point: the GPU form (see "Precision")
// and the world point as hi + lo (for positions and tessellation levels), interleaved, relative to
// `center` in GPU units. Each patch's frame and forward differences are computed in double, split
// over the cores.
void packGpuPatches(const std::vector<Patch>& patches, size_t first, const glm::dvec3& center, double perUnit,
                    float* positions, float* frameTexels) {
  const size_t added = patches.size() - first;
  const unsigned parts = threadsFor(added * 8);
  runParts(parts, [&](unsigned part) {
    const size_t end = first + size_t(partBound(Index(added), parts, part + 1));
    for (size_t p = first + size_t(partBound(Index(added), parts, part)); p < end; ++p) {
      const Patch& patch = patches[p];
      const GpuPatch gpu = gpuForm(patch);
      const PatchFrameCpu& frame = gpu.frame;
      float* texels = frameTexels + (p - first) * kFloatsPerFrame;
      splitHiLo((frame.origin - center) * perUnit, texels, texels + 3);
      for (int axis = 0; axis < 3; ++axis)
        for (int c = 0; c < 3; ++c) texels[6 + 3 * axis + c] = frame.axes[axis][c];
      float* point = positions + (p - first) * kFloatsPerPatch;
      for (int k = 0; k < kControlPointsPerPatch; ++k, point += kFloatsPerPoint) {
        const glm::vec3 local(inUnits(patch.kind, k, gpu.cp[k], perUnit));
        point[0] = local.x, point[1] = local.y, point[2] = local.z;
        if (isPositionPoint(patch.kind, k)) {
          splitHiLo(((patch.origin - center) + drawnPoint(patch, k)) * perUnit, point + 3, point + 6);
          continue;
        }
        // A cap's vector and parameter slots: the value in hi, its f_j in lo (GpuPatch).
        const glm::vec3 hi = roundToFloat(inUnits(patch.kind, k, capSharedSlot(patch, k), perUnit));
        glm::vec3 lo(0.0f);
        if (k >= 1 && k <= 4) lo = roundToFloat(gpu.capSecondWorld[size_t(k - 1)] * perUnit);
        if (k >= 12) lo = roundToFloat(gpu.capSecond[size_t(k - 12)] * perUnit);
        for (int c = 0; c < 3; ++c) point[3 + c] = hi[c], point[6 + c] = lo[c];
      }
    }
  });
}

}  // namespace

void PatchRenderer::placeBounds(const std::vector<Patch>& patches, size_t first, bool sameSequence) {
  // Bounding box of the position-valued control points; the centre keeps float precision. Over a
  // sequence kept on the GPU the centre stays (its slots were stored relative to it) and the box
  // takes in the new patches only (from `first`).
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  if (sameSequence) lo = boundsMin_, hi = boundsMax_;
  for (size_t p = first; p < patches.size(); ++p)
    for (int k = 0; k < kControlPointsPerPatch; ++k)
      if (isPositionPoint(patches[p].kind, k)) {
        lo = glm::min(lo, patches[p].origin + patches[p].cp[k]);
        hi = glm::max(hi, patches[p].origin + patches[p].cp[k]);
      }
  if (patches.empty()) lo = hi = glm::dvec3(0.0);
  boundsMin_ = lo;
  boundsMax_ = hi;
  if (!sameSequence) center_ = 0.5 * (lo + hi);
  radius_ = 0.5 * glm::length(hi - lo);
  if (!(radius_ > 0.0) || !std::isfinite(radius_)) radius_ = std::max(1e-12 * glm::length(center_), 1e-300);
  if (!sameSequence) unit_ = std::ldexp(1.0, std::ilogb(radius_));
}

void PatchRenderer::setPatches(const std::vector<Patch>& patches, uint64_t stableStamp, size_t stableCount) {
  Impl& g = *impl_;
  const SlotLayout layout = layoutSlots(patches.size(), stableStamp, stableCount, stableStamp_, stableOnGpu_);
  stableStamp_ = stableStamp;
  stableOnGpu_ = layout.stableSlots;
  reusedPatches_ = layout.reused;
  patchCount_ = static_cast<int>(patches.size());
  drawRanges_.clear();
  if (layout.stableCount > 0) drawRanges_.push_back({0, layout.stableCount, 0});
  if (layout.tailCount > 0) drawRanges_.push_back({layout.stableSlots, layout.tailCount, layout.stableCount});
  placeBounds(patches, layout.reused, layout.sameSequence);

  // Written in place (this runs every frame of a vertex drag); only the patches not already on
  // the GPU.
  const size_t added = patches.size() - layout.reused;
  const std::unique_ptr<float[]> positions(new float[added * kFloatsPerPatch]);  // every float written below
  std::vector<float> frameTexels(added * kFloatsPerFrame);
  std::vector<int32_t> kindRings;
  const double transitionUnitLength = packKindsAndTransitions(patches, layout, kindRings);
  packGpuPatches(patches, layout.reused, center_, 1.0 / unit_, positions.get(), frameTexels.data());
  impl_->transitionUnitLength = transitionUnitLength;

  // The new stable patches go after the valid ones, the rest after every stable slot.
  const size_t reused = layout.reused, stableSlots = layout.stableSlots, tailCount = layout.tailCount;
  const size_t newStable = layout.stableCount - reused;
  const size_t pointBytes = kFloatsPerPatch * sizeof(float), frameBytes = kFloatsPerFrame * sizeof(float);
  g.patchPositions = reserveBuffer(g.patchPositions, &g.positionsCapacity, layout.validBefore * pointBytes, layout.totalSlots * pointBytes);
  writeBuffer(GL_ARRAY_BUFFER, g.patchPositions, reused, newStable, pointBytes, positions.get());
  writeBuffer(GL_ARRAY_BUFFER, g.patchPositions, stableSlots, tailCount, pointBytes, positions.get() + newStable * kFloatsPerPatch);
  g.frameBuffer = reserveBuffer(g.frameBuffer, &g.frameCapacity, layout.validBefore * frameBytes, layout.totalSlots * frameBytes);
  writeBuffer(GL_TEXTURE_BUFFER, g.frameBuffer, reused, newStable, frameBytes, frameTexels.data());
  writeBuffer(GL_TEXTURE_BUFFER, g.frameBuffer, stableSlots, tailCount, frameBytes, frameTexels.data() + newStable * kFloatsPerFrame);
  g.kindBuffer = reserveBuffer(g.kindBuffer, &g.kindCapacity, 0, kindRings.size() * sizeof(int32_t));
  writeBuffer(GL_TEXTURE_BUFFER, g.kindBuffer, 0, kindRings.size(), sizeof(int32_t), kindRings.data());

  std::vector<uint32_t> slotOfPatch(patches.size());
  turnOfPatch_.resize(patches.size());
  for (size_t p = 0; p < patches.size(); ++p) {
    slotOfPatch[p] = uint32_t(layout.slotOf(p));
    turnOfPatch_[p] = patches[p].ringTurn;
  }
  // The draw selection's rows and bounds, where draws choose per region (setRegionDetail).
  if (regionDetail_) selection_.build(patches, slotOfPatch);
  else selection_.build({}, {});
  const std::vector<int32_t>& rowSlots = selection_.rowSlots();
  glBindBuffer(GL_TEXTURE_BUFFER, g.rowSlotBuffer);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(std::max<size_t>(rowSlots.size(), 1) * sizeof(int32_t)),
               rowSlots.empty() ? nullptr : rowSlots.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);

  g.attachBuffers();

  // Overlays are stored relative to the centre too: re-upload them when it moved.
  if (!layout.sameSequence) {
    g.uploadOverlay(g.netVao, g.netBuffer, g.netPointsWorld, g.netColors, center_, unit_);
    g.uploadOverlay(g.poleVao, g.poleBuffer, g.polesWorld, {glm::vec3(1.0f, 0.85f, 0.1f)}, center_, unit_);
  }
}

void PatchRenderer::reserveFor(size_t regular, size_t other) {
  Impl& g = *impl_;
  const size_t slots = std::max(stableOnGpu_, regular) + other, inUse = slotsInUse();
  const size_t pointBytes = kFloatsPerPatch * sizeof(float), frameBytes = kFloatsPerFrame * sizeof(float);
  if (slots * pointBytes <= g.positionsCapacity && slots * frameBytes <= g.frameCapacity) return;
  // What is drawn now stays valid: every slot in use is kept.
  g.patchPositions = reserveBuffer(g.patchPositions, &g.positionsCapacity, inUse * pointBytes, slots * pointBytes);
  g.frameBuffer = reserveBuffer(g.frameBuffer, &g.frameCapacity, inUse * frameBytes, slots * frameBytes);
  g.attachBuffers();
}

size_t PatchRenderer::slotsInUse() const {
  size_t slots = 0;
  for (const DrawRange& range : drawRanges_) slots = std::max(slots, range.firstSlot + range.count);
  return slots;
}

void PatchRenderer::setControlMesh(const PolyMesh& mesh, const std::vector<NetSegment>& segments) {
  Impl& g = *impl_;
  g.netPointsWorld.clear();
  g.netColors.clear();
  g.netPointsWorld.reserve(segments.size() * 2);
  g.netColors.reserve(segments.size() * 2);
  for (const NetSegment& segment : segments) {
    const glm::vec3 color(netSegmentColor(segment.sharpness));
    g.netPointsWorld.push_back(mesh.points[size_t(segment.a)]);
    g.netPointsWorld.push_back(mesh.points[size_t(segment.b)]);
    g.netColors.insert(g.netColors.end(), {color, color});
  }
  g.netVertexCount = static_cast<GLsizei>(g.netPointsWorld.size());
  g.uploadOverlay(g.netVao, g.netBuffer, g.netPointsWorld, g.netColors, center_, unit_);
}

void PatchRenderer::setControlMesh(const PolyMesh& mesh) { setControlMesh(mesh, controlNetSegments(mesh)); }

void PatchRenderer::setPoleMarkers(const std::vector<Point>& poles) {
  Impl& g = *impl_;
  g.polesWorld = poles;
  g.poleCount = static_cast<GLsizei>(poles.size());
  g.uploadOverlay(g.poleVao, g.poleBuffer, g.polesWorld, {glm::vec3(1.0f, 0.85f, 0.1f)}, center_, unit_);
}

// [SECTION] Drawing

void PatchRenderer::setEyeUniforms(unsigned program, const ViewParams& view) const {
  // Projection times the view's rotation (its translation is the eye, applied in patch_frame.glsl
  // from the double eye as hi + lo).
  // In GPU units p' = p / unit: clip = P R (unit p'), and a perspective clip scaled by 1 / unit
  // (homogeneous: the same picture) keeps float-sized entries and w = depth / unit.
  const glm::dmat4 rotation(glm::dmat3(view.view));
  const glm::dmat4 toWorld = glm::scale(glm::dmat4(1.0), glm::dvec3(unit_));
  const double clipScale = isPerspective(view) ? 1.0 / unit_ : 1.0;
  setUniform(program, "u_viewRotationProjection", glm::mat4(clipScale * (view.proj * toWorld * rotation)));
  glm::vec3 eyeHi, eyeLo;
  splitHiLo((view.eye - center_) / unit_, glm::value_ptr(eyeHi), glm::value_ptr(eyeLo));
  setUniform(program, "u_eyeHi", eyeHi);
  setUniform(program, "u_eyeLo", eyeLo);
  setUniform(program, "u_patchFrames", kFrameTextureUnit);
  setUniform(program, "u_patchKinds", kKindTextureUnit);
  glActiveTexture(GL_TEXTURE0 + kFrameTextureUnit);
  glBindTexture(GL_TEXTURE_BUFFER, impl_->frameTexture);
  glActiveTexture(GL_TEXTURE0 + kKindTextureUnit);
  glBindTexture(GL_TEXTURE_BUFFER, impl_->kindTexture);
  setUniform(program, "u_patchPoints", kPointTextureUnit);
  setUniform(program, "u_drawItems", kItemTextureUnit);
  setUniform(program, "u_rowSlots", kRowSlotTextureUnit);
  const std::pair<int, GLuint> texelBuffers[] = {
      {kPointTextureUnit, impl_->pointTexture}, {kItemTextureUnit, impl_->itemTexture}, {kRowSlotTextureUnit, impl_->rowSlotTexture}};
  for (const auto& [unit, texture] : texelBuffers) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_BUFFER, texture);
  }
  glActiveTexture(GL_TEXTURE0);
}

void PatchRenderer::setTessellationUniforms(unsigned program, const ViewParams& view,
                                            const ShadingParams& shading) const {
  setEyeUniforms(program, view);
  setUniform(program, "u_viewportSize", glm::vec2(view.viewport.z, view.viewport.w));
  setUniform(program, "u_tessPixels", std::max(shading.tessPixels, 0.5f));
  setUniform(program, "u_maxTessLevel", static_cast<float>(std::clamp(shading.maxTessLevel, 1, 64)));
  setUniform(program, "u_fixedTessLevel", static_cast<float>(std::min(shading.fixedTessLevel, 64)));
  setUniform(program, "u_transitionDensity", transitionDensity(view, shading));
  // Perspective: w = depth (in GPU units), near = P[3][2] / (P[2][2] - 1); orthographic: w = 1.
  const double near = isPerspective(view) ? view.proj[3][2] / (view.proj[2][2] - 1.0) / unit_ : 1.0;
  setUniform(program, "u_nearDepth", float(std::isfinite(near) && near > 0.0 ? near : 1e-30));
}

int PatchRenderer::transitionDensity(const ViewParams& view, const ShadingParams& shading) const {
  const double unitLength = impl_->transitionUnitLength;
  if (!(unitLength > 0.0)) return 0;
  // Pixels per world unit at the model centre: proj[1][1] maps view-space y to clip y; / w.
  const glm::dvec4 clip = view.proj * view.view * glm::dvec4(center_, 1.0);
  const double pixelsPerUnit = 0.5 * view.viewport.w * view.proj[1][1] / std::max(clip.w, 1e-9 * radius_);
  const double segments = unitLength * pixelsPerUnit / std::max(double(shading.tessPixels), 0.5);
  return static_cast<int>(std::clamp(std::lround(std::log2(std::max(segments, 1e-30))), -64L, 64L));
}

void PatchRenderer::startGpuTimer() {
  // GPU time of the previous use of this query slot (non-blocking when available).
  Impl& g = *impl_;
  const int slot = g.timerIndex;
  if (g.timerPending[slot]) {
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(g.timerQueries[slot], GL_QUERY_RESULT, &nanoseconds);
    stats_.gpuMilliseconds = static_cast<double>(nanoseconds) * 1e-6;
  }
  glBeginQuery(GL_TIME_ELAPSED, g.timerQueries[slot]);
  g.timerPending[slot] = true;
  g.timerIndex = 1 - slot;
}

void PatchRenderer::setShadingUniforms(unsigned program, const ViewParams& view, const ShadingParams& shading,
                                       const DisplayFlags& flags) const {
  const glm::vec3 eye((view.eye - center_) / unit_);  // for highlight lines, relative to the centre
  // Light lines: direction B, across E = W x B, plane normal W = B x E (docs/shading.md,
  // Highlight lines).
  const glm::vec3 B = glm::normalize(shading.highlightDir);
  const glm::vec3 W = perpendicularTo(B, shading.highlightPlaneNormal);
  const glm::vec3 E = glm::cross(W, B);
  const float radius = static_cast<float>(radius_ / unit_);  // GPU units
  // Key light fixed in view space (upper left, in front), expressed in world axes.
  const glm::vec3 keyView = glm::length(shading.keyLightView) > 1e-6f ? glm::normalize(shading.keyLightView)
                                                                       : glm::vec3(0.0f, 0.0f, 1.0f);
  const glm::vec3 keyWorld = glm::normalize(glm::transpose(glm::mat3(view.view)) * keyView);

  setTessellationUniforms(program, view, shading);
  setUniform(program, "u_colormap", static_cast<int>(shading.colormap));
  // The GPU's K and H are in its units: K unit^2, H unit.
  const double curvatureUnit = shading.mode == ShadingParams::Mode::Gaussian ? unit_ * unit_ : unit_;
  setUniform(program, "u_rangeLow", floatInRange(shading.range.low * curvatureUnit));
  setUniform(program, "u_rangeHigh", floatInRange(shading.range.high * curvatureUnit));
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
}

void PatchRenderer::drawSurface(const ViewParams& view, const ShadingParams& shading, const DisplayFlags& flags) {
  const GLuint program = surfaceProgram(shading.mode, flags.wireframe, false);
  setShadingUniforms(program, view, shading, flags);
  glUseProgram(program);
  glBindVertexArray(impl_->patchVao);
  glPatchParameteri(GL_PATCH_VERTICES, kControlPointsPerPatch);
  // Push the surface back a little so boundary curves and markers on it stay visible.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 2.0f);
  if (regionDetail_ && shading.fixedTessLevel <= 0) {
    DrawSelectionSettings settings;
    settings.tessPixels = std::max(shading.tessPixels, 0.5f);
    settings.maxTessLevel = shading.maxTessLevel;
    settings.viewportHeight = view.viewport.w;
    DrawSelectionStats counted;
    const std::vector<DrawItem> items = selection_.select(view, settings, &counted);
    stats_.drawnPrimitives = counted.items;
    stats_.drawnPatches = counted.patches;
    stats_.culledPatches = counted.culled;
    drawItems(view, shading, flags, program, items);
  } else {
    setUniform(program, "u_useItems", 0);
    stats_.drawnPrimitives = stats_.drawnPatches = size_t(patchCount_);
    stats_.culledPatches = 0;
    drawPatchRuns(drawRanges_, largestTessLevel(shading));
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
}

void PatchRenderer::drawItems(const ViewParams& view, const ShadingParams& shading, const DisplayFlags& flags,
                              unsigned program, std::vector<DrawItem> items) {
  Impl& g = *impl_;
  // Lone patches first, drawn by `program`, then the groups of sectors by its SECTOR_GROUPS twin.
  const auto firstGroup = std::stable_partition(items.begin(), items.end(), [](const DrawItem& item) { return item.groupLog2 == 0; });
  const size_t lone = size_t(firstGroup - items.begin());
  // Per item two texels (patch.tesc's u_drawItems); item i is drawn as vertices 16 i .. 16 i + 15
  // (patch.vert fetches its slot's points).
  std::vector<int32_t> texels(items.size() * 8, 0);
  for (size_t i = 0; i < items.size(); ++i) {
    const DrawItem& item = items[i];
    int32_t* texel = texels.data() + 8 * i;
    texel[0] = int32_t(item.slot);
    texel[1] = item.rowStart;
    texel[2] = item.sector;
    texel[3] = std::max(item.rowSize, 1);
    texel[4] = int32_t(uint32_t(item.groupLog2) | uint32_t(item.innerExponent + 1) << 8 | uint32_t(item.outerExponent + 1) << 16);
  }
  glBindBuffer(GL_TEXTURE_BUFFER, g.itemBuffer);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(std::max<size_t>(texels.size(), 8) * sizeof(int32_t)),
               texels.empty() ? nullptr : texels.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  glBindTexture(GL_TEXTURE_BUFFER, g.itemTexture);  // a new store: attached again
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32I, g.itemBuffer);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  const auto drawRange = [&](GLuint drawing, size_t begin, size_t end) {
    if (begin == end) return;
    glUseProgram(drawing);
    setUniform(drawing, "u_useItems", 1);
    // Runs whose items tessellate into at most kMaxVerticesPerDraw vertices (drawPatchRuns).
    std::vector<GLint> firsts;
    std::vector<GLsizei> counts;
    for (size_t first = begin; first < end;) {
      size_t last = first, vertices = 0;
      while (last < end && (last == first || vertices + items[last].vertexBound <= size_t(kMaxVerticesPerDraw)))
        vertices += items[last++].vertexBound;
      firsts.push_back(static_cast<GLint>(first * kControlPointsPerPatch));
      counts.push_back(static_cast<GLsizei>((last - first) * kControlPointsPerPatch));
      first = last;
    }
    glMultiDrawArrays(GL_PATCHES, firsts.data(), counts.data(), static_cast<GLsizei>(firsts.size()));
    setUniform(drawing, "u_useItems", 0);
  };
  drawRange(program, 0, lone);
  if (lone < items.size()) {
    const GLuint groups = surfaceProgram(shading.mode, flags.wireframe, true);
    setShadingUniforms(groups, view, shading, flags);
    drawRange(groups, lone, items.size());
  }
}

void PatchRenderer::drawPatchBoundaries(const ViewParams& view, const DisplayFlags& flags) {
  Impl& g = *impl_;
  const GLuint program = g.shaders->program(kBoundaryProgram);
  setEyeUniforms(program, view);
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
  drawPatchRuns(drawRanges_, 1);
}

void PatchRenderer::drawControlNet(unsigned overlay, bool overSurface) {
  Impl& g = *impl_;
  // Dark lines over the surface, light ones over the background when the surface is hidden (the
  // dark net vanished against the dark background). With the surface shown, the parts of the net
  // behind it are drawn faintly first, so the net reads as one piece, as CAD viewers show hidden lines.
  const glm::vec3 netColour = overSurface ? glm::vec3(0.06f, 0.06f, 0.08f) : glm::vec3(0.85f, 0.87f, 0.9f);
  setUniform(overlay, "u_roundPoints", 0);
  setUniform(overlay, "u_pointSize", 1.0f);
  setUniform(overlay, "u_colorOverride", glm::vec4(netColour, 1.0f));
  glUseProgram(overlay);
  glBindVertexArray(g.netVao);
  if (overSurface) {
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

void PatchRenderer::drawPoleMarkers(unsigned overlay) {
  Impl& g = *impl_;
  setUniform(overlay, "u_depthBias", 0.002f);
  setUniform(overlay, "u_roundPoints", 1);
  setUniform(overlay, "u_pointSize", 11.0f);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glUseProgram(overlay);
  glBindVertexArray(g.poleVao);
  glDrawArrays(GL_POINTS, 0, g.poleCount);
  glDisable(GL_PROGRAM_POINT_SIZE);
}

void PatchRenderer::draw(const ViewParams& view, const ShadingParams& shading,
                         const DisplayFlags& flags) {
  Impl& g = *impl_;
  glViewport(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.w);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);  // two-sided surfaces
  glDisable(GL_BLEND);
  glFinish();  // what came before is not this view's (wallMilliseconds)
  const auto wallStart = std::chrono::steady_clock::now();
  startGpuTimer();
  stats_.patchCount = patchCount_;

  if (patchCount_ > 0 && (flags.surface || flags.wireframe)) drawSurface(view, shading, flags);
  if (patchCount_ > 0 && flags.patchBoundaries) drawPatchBoundaries(view, flags);

  const GLuint overlay = g.shaders->program(kOverlayProgram);
  setEyeUniforms(overlay, view);
  setUniform(overlay, "u_alpha", 1.0f);
  setUniform(overlay, "u_colorOverride", glm::vec4(0.0f));
  if (flags.controlNet && g.netVertexCount > 0) drawControlNet(overlay, flags.surface);
  if (flags.poleMarkers && g.poleCount > 0) drawPoleMarkers(overlay);
  glBindVertexArray(0);
  glUseProgram(0);
  glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  stats_.wallMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wallStart).count();
}

void PatchRenderer::drawControlNetOver(const ViewParams& view) {
  Impl& g = *impl_;
  if (g.netVertexCount == 0) return;
  glViewport(view.viewport.x, view.viewport.y, view.viewport.z, view.viewport.w);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  const GLuint overlay = g.shaders->program(kOverlayProgram);
  setEyeUniforms(overlay, view);
  setUniform(overlay, "u_alpha", 1.0f);
  drawControlNet(overlay, true);
  glBindVertexArray(0);
  glUseProgram(0);
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
  drawPatchRuns(drawRanges_, largestTessLevel(shading));
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
    s.gaussian = double(d[2]) / (unit_ * unit_);  // from GPU units back to the world's
    s.mean = double(d[3]) / unit_;
    s.patch = patchIndexOfSlot(size_t(d[7]));
    // The GPU evaluates ring patches turned (packKindLevelJumps): back to the patch's parameter.
    double u = s.u, v = s.v;
    if (s.patch >= 0) turnedParameter(&u, &v, turnOfPatch_[size_t(s.patch)]);
    s.u = float(u), s.v = float(v);
    // Where draw() places the vertex, relative to the eye: back to world coordinates in double.
    s.position = view.eye + unit_ * glm::dvec3(d[4], d[5], d[6]);
  }
  return samples;
}

}  // namespace polarview
