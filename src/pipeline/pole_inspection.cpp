// The pole inspector's numbers (see pole_inspection.h).
#include "pipeline/pole_inspection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/mesh/manifold_split.h"
#include "core/mesh/ngon_to_fan.h"
#include "core/mesh/constants.h"
#include "core/mesh/topology.h"
#include "core/spline/patch_extraction.h"
#include "core/spline/pole_taylor.h"
#include "core/spline/ring_curvature.h"
#include "core/subdiv/adaptive_refiner.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/refiner.h"

namespace polarview {
namespace {

PolarConfig findPole(const PolyMesh& input, Index vertex) {
  ManifoldSplit split;
  MeshTopology topo;
  const PolyMesh& mesh = refinableMesh(input, split, topo);
  for (PolarConfig& config : findPolarConfigs(mesh, topo))
    if (config.refinable && config.pole == vertex) return config;
  throw std::invalid_argument("inspectPole: vertex " + std::to_string(vertex) + " is not a pole of the mesh");
}

// Catmull-Clark around an extraordinary vertex: ring m = the regular patches of level m nearest the
// vertex (the feature-adaptive refinement makes a ring of them each level), K at their centres,
// angles in the tangent plane of the vertex's limit normal.
void catmullClarkRings(const PolyMesh& mesh, Index vertex, int rings, PoleInspection& out) {
  AdaptiveRefinement refinement(mesh, RefineOptions{Scheme::CatmullClark, rings, false});
  const PatchSet set = extractPatches(refinement);
  const Point centre = mesh.points[size_t(vertex)];
  // The vertex's limit position and normal: from the end caps at the finest level touching it.
  Point pole(0.0), normal(0.0);
  double nearest = std::numeric_limits<double>::infinity();
  for (const Patch& patch : set.patches) {
    if (patch.kind != PatchKind::EndCap || patch.level != rings) continue;
    const SurfacePoint at = evaluatePatch(patch, 0.0, 0.0);  // the face's first corner
    const double d = glm::length(at.position - centre);
    if (d < nearest) nearest = d, pole = at.position;
    normal += at.normal;
  }
  if (!(glm::length(normal) > 0.0)) return;
  normal = glm::normalize(normal);
  Point e1 = glm::cross(normal, std::abs(normal.x) < 0.9 ? Point(1, 0, 0) : Point(0, 1, 0));
  e1 = glm::normalize(e1);
  const Point e2 = glm::cross(normal, e1);
  for (int m = 1; m < rings; ++m) {
    struct Sample {
      double angle, K;
    };
    std::vector<Sample> samples;
    std::vector<std::pair<double, const Patch*>> candidates;
    double closest = std::numeric_limits<double>::infinity();
    for (const Patch& patch : set.patches)
      if (patch.level == m && patch.kind == PatchKind::Regular) {
        const double d = glm::length(evaluatePatch(patch, 0.5, 0.5).position - pole);
        candidates.emplace_back(d, &patch);
        closest = std::min(closest, d);
      }
    // A circle around the vertex through the nearest regular patches: dense samples of the patches
    // within the band of radii where the circle runs, so that the angle alone tells them apart.
    std::vector<std::pair<double, Sample>> dense;  // (radius, sample)
    constexpr int kPerSide = 12;
    for (const auto& [d, patch] : candidates) {
      if (d > 1.6 * closest) continue;
      for (int a = 0; a < kPerSide; ++a)
        for (int b = 0; b < kPerSide; ++b) {
          const SurfacePoint at = evaluatePatch(*patch, (a + 0.5) / kPerSide, (b + 0.5) / kPerSide);
          const Point r = at.position - pole;
          const double angle = std::atan2(glm::dot(r, e2), glm::dot(r, e1)) / (2.0 * kPi);
          dense.push_back({glm::length(r - glm::dot(r, normal) * normal), {angle < 0.0 ? angle + 1.0 : angle, at.gaussian}});
        }
    }
    const double circle = closest;  // the nearest patches' centres lie about this far out
    for (const auto& [radius, sample] : dense)
      if (std::abs(radius - circle) < 0.04 * circle) samples.push_back(sample);
    if (samples.empty()) continue;
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.angle < b.angle; });
    PoleRingCurves ring;
    ring.m = m;
    ring.minK = ring.maxK = samples[0].K;
    for (const Sample& s : samples) ring.minK = std::min(ring.minK, s.K), ring.maxK = std::max(ring.maxK, s.K);
    ring.deviation = ring.maxK - ring.minK;
    // Resampled at uniform angles (nearest sample: the patches' centres are not uniform in angle).
    for (int a = 0; a < kInspectorAngles; ++a) {
      const double at = double(a) / kInspectorAngles;
      const auto next = std::lower_bound(samples.begin(), samples.end(), at, [](const Sample& s, double x) { return s.angle < x; });
      const Sample& s = next == samples.end() ? samples.back() : *next;
      ring.kAlongAngle.push_back(s.K);
    }
    out.rings.push_back(std::move(ring));
  }
  out.limit = pole;
  out.normal = normal;
}

}  // namespace

std::vector<Index> modelPoles(const PolyMesh& input) { return surveyPoles(input, 0).poles; }

PoleSurvey surveyPoles(const PolyMesh& input, size_t listed) {
  ManifoldSplit split;
  MeshTopology topo;
  const PolyMesh& mesh = refinableMesh(input, split, topo);
  return surveyPoles(input, findPolarConfigs(mesh, topo), listed);
}

PoleSurvey surveyPoles(const PolyMesh& input, const std::vector<PolarConfig>& configs, size_t listed) {
  PoleSurvey survey;
  for (const PolarConfig& config : configs)
    if (config.refinable) survey.poles.push_back(config.pole);
  for (const RejectedGroup& group : groupRejectedCandidates(configs)) {
    RejectedPoleGroup out{polarRejectionWords(group.rejection), int(group.members.size()), {}};
    for (size_t k = 0; k < group.members.size() && k < listed; ++k) {
      const PolarConfig& config = configs[group.members[k]];
      out.nearest.push_back({config.pole, config.valence, config.reason});
    }
    survey.rejectedCount += out.count;
    survey.rejected.push_back(std::move(out));
  }
  survey.fanFaces = countFanFaces(input);
  return survey;
}

PoleInspection inspectPole(const PolyMesh& mesh, Index vertex, SchemeChoice scheme, int rings) {
  const PolarConfig config = findPole(mesh, vertex);
  const RefineOptions options = refineOptionsFor(scheme, 0);
  const SchemeTraits& traits = schemeTraits(options.scheme);
  PoleInspection out;
  out.scheme = scheme;
  out.vertex = vertex;
  out.valence = config.valence;
  std::string why;
  out.byScheme = traits.polar() && schemeRefinesPole(options.scheme, config, &why);
  if (!out.byScheme) {
    out.directional = true;
    out.note = traits.polar() ? why + ": Catmull-Clark refines this pole; K oscillates around it"
                              : "Catmull-Clark: an extraordinary vertex of valence " + std::to_string(config.valence) +
                                    "; K oscillates n-fold around it and has no limit there";
    catmullClarkRings(mesh, vertex, std::min(rings, 10), out);
    return out;
  }
  // The pole's expansion (32) at level 0 and its rings, from its own links (as `pole --rings`).
  const Refinement refinement(mesh, options);
  const RefinedLevel& level = refinement.level(0);
  size_t k = 0;
  while (k < level.poles.size() && level.poles[k].pole != vertex) ++k;
  if (k == level.poles.size()) throw std::logic_error("inspectPole: the scheme's pole list lacks vertex " + std::to_string(vertex));
  const TaylorCoefficients& taylor = level.poleTaylor[k];
  const PoleDifferential d = analyzePole(taylor);
  out.hasExpansion = true;
  out.limit = d.limit;
  out.normal = d.normal;
  std::copy(std::begin(taylor.p), std::end(taylor.p), out.p.begin());
  out.curvatureDefined = d.curvatureDefined;
  out.K = d.gaussian;
  out.H = d.mean;
  out.directional = traits.taylorOrder == 2 && !traits.curvatureContinuous;
  out.deviationFromPole = d.curvatureDefined && traits.curvatureContinuous;
  if (traits.taylorOrder < 2) out.note = std::string(traits.label) + " is C1 at the pole: K and H there are not defined";
  else if (out.directional) out.note = std::string(traits.label) + " is not C2 for finite n: K at the pole depends on the direction";
  else out.note = std::string(traits.label) + " is C2 at the pole: the rings' K tends to the pole's";
  // C2PS doubles the valence a level: stop where a ring would exceed 2^16 columns.
  int count = rings;
  if (!traits.keepsValence)
    while (count > 1 && double(config.valence) * std::ldexp(1.0, count) > double(1 << 16)) --count;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const RingCurvature& r : ringCurvatures(level.poleGrids[k], options.scheme, options.uniformFirstStep, count,
                                               d.curvatureDefined ? d.gaussian : nan, d.curvatureDefined ? d.mean : nan,
                                               d.normal, 5, kInspectorAngles)) {
    PoleRingCurves ring;
    ring.m = r.m;
    ring.minK = r.minK;
    ring.maxK = r.maxK;
    ring.deviation = out.deviationFromPole ? r.maxAbsDeltaK : r.maxK - r.minK;
    ring.kAlongAngle = r.kAlongAngle;
    out.rings.push_back(std::move(ring));
  }
  return out;
}

}  // namespace polarview

namespace polarview {

std::vector<Patch> zoomAboutPole(const std::vector<Patch>& patches, int pole, int firstRing, int rings, const Point& centre) {
  const double s = std::ldexp(1.0, firstRing);
  std::vector<Patch> out;
  for (const Patch& patch : patches) {
    if (patch.pole != pole) continue;
    const bool ring = patch.kind == PatchKind::PolarRing && patch.ring >= firstRing && patch.ring < firstRing + rings;
    const bool cap = patch.kind == PatchKind::PoleCap && patch.level >= firstRing && patch.level < firstRing + rings;
    if (!ring && !cap) continue;
    // Positions relative to the origin and vectors scale alike; the origin moves about the centre.
    Patch zoomed = patch;
    zoomed.origin = centre + s * (patch.origin - centre);
    for (Point& c : zoomed.cp) c *= s;
    for (Point& c : zoomed.capExtra) c *= s;
    out.push_back(zoomed);
  }
  return out;
}

}  // namespace polarview
