#include "pipeline/pole_report.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

// C2PS doubles the valence each level: the last ring's columns stay within 2^18. A limit that
// depends on the input is bad input (the CLI's exit 1), checked before anything is printed.
void checkC2psRings(const std::string& file, const RefinedLevel& level, int rings) {
  for (size_t k = 0; k < level.poles.size(); ++k)
    if (double(level.poleGrids[k].n) * std::pow(2.0, rings) > double(1 << 18))
      throw InputError(file, 0, "--rings " + std::to_string(rings) + " would give C2PS a valence over 2^18 at pole vertex " +
                                    std::to_string(level.poles[k].pole) + " (valence " + std::to_string(level.poleGrids[k].n) +
                                    "); at most --rings " +
                                    std::to_string(std::max(0, int(std::floor(std::log2(double(1 << 18) / level.poleGrids[k].n))))));
}

// One pole's object of `pole --json`: limit, normal, K and H (null where undefined), p0..p5, and
// rings 1..M (paper (6), r in [2, 4] 2^-m), refined from the pole's own links 0..5, which it returns.
std::vector<RingCurvature> writePole(ReportBuilder& w, const SchemeVariant& variant, const RefinedLevel& level, size_t k,
                                     const PoleDifferential& d, int rings) {
  const TaylorCoefficients& t = level.poleTaylor[k];
  w.beginObject().field("vertex", level.poles[k].pole).field("valence", level.poles[k].valence);
  w.field("scheme", schemeVariantName(variant)).field("limit", d.limit).field("normal", d.normal);
  if (d.curvatureDefined) w.field("gaussian_curvature", d.gaussian).field("mean_curvature", d.mean);
  else w.key("gaussian_curvature").null().key("mean_curvature").null();
  w.key("p").beginArray();
  for (const Point& p : t.p) w.value(p);
  w.endArray();
  std::vector<RingCurvature> ringStats;
  if (rings > 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // Spokes along the input's column edges and middles: 2n of them.
    const double poleK = d.curvatureDefined ? d.gaussian : nan;
    ringStats = ringCurvatures(level.poleGrids[k], variant.scheme, variant.uniformFirstStep, rings, poleK,
                               d.curvatureDefined ? d.mean : nan, d.normal, 5, 0, 2 * level.poles[k].valence);
    w.field("spoke_sign_changes", spokeSignChanges(ringStats, poleK));
    w.key("rings").beginArray();
    for (const RingCurvature& r : ringStats) {
      w.beginObject().field("m", r.m).field("valence", r.valence);
      if (d.curvatureDefined) w.field("max_abs_dK", r.maxAbsDeltaK);
      else w.key("max_abs_dK").null();
      w.field("K_min", r.minK).field("K_max", r.maxK);
      if (d.curvatureDefined) w.field("max_abs_dH", r.maxAbsDeltaH);
      else w.key("max_abs_dH").null();
      w.field("H_min", r.minH).field("H_max", r.maxH).field("dK_dr_sign_changes", r.spokeSignChanges).endObject();
    }
    w.endArray();
  }
  w.endObject();
  return ringStats;
}

}  // namespace

PoleReport makePoleReport(const PolyMesh& mesh, const std::string& file, const SchemeVariant& variant, int rings) {
  // Level 0 only: the expansion is that of the input's own configuration (the Section-6 variant
  // leaves links 0 and 1, hence p0..p5, unchanged).
  PoleReport report{Refinement(mesh, {variant.scheme, 0, variant.uniformFirstStep}, file), {}, {}};
  const RefinedLevel& level = report.refinement.level(0);
  if (rings > 0 && !schemeTraits(variant.scheme).keepsValence) checkC2psRings(file, level, rings);
  ReportBuilder w(file);
  w.beginObject().key("poles").beginArray();
  for (size_t k = 0; k < level.poles.size(); ++k) {
    const PoleDifferential d = analyzePole(level.poleTaylor[k]);
    report.poles.push_back({d, writePole(w, variant, level, k, d, rings)});
  }
  w.endArray().endObject();
  report.value = w.take();
  return report;
}

}  // namespace polarview
