// What `polarview pole` reports on each refinable pole of a mesh: limit, normal, K and H from the
// Taylor expansion (32), p0..p5, and the curvature over spline rings 1..M; the CLI prints it as text
// or JSON, the Python module's pole() converts the tree the JSON is printed from.
#pragma once

#include <string>
#include <vector>

#include "core/spline/pole_taylor.h"
#include "core/spline/ring_curvature.h"
#include "core/subdiv/refiner.h"
#include "pipeline/report_value.h"

namespace polarview {

struct PoleReportEntry {
  PoleDifferential differential;
  std::vector<RingCurvature> rings;  // rings 1..M (empty without rings)
};

struct PoleReport {
  Refinement refinement;  // level 0 only: the poles of the input's own configurations
  std::vector<PoleReportEntry> poles;  // parallel to refinement.level(0).poles
  ReportValue value;                   // `pole --json`'s object {"poles": [...]} (reportJson prints it)
};

// The report of `variant` (a polar scheme) on `mesh`, with `rings` spline rings per pole (0: none;
// paper (6), r in [2, 4] 2^-m). Throws InputError naming `file` for bad meshes, a C2PS ring count
// whose valence would pass 2^18, or a non-finite number in the result. [O(poles rings n_rings)]
PoleReport makePoleReport(const PolyMesh& mesh, const std::string& file, const SchemeVariant& variant, int rings);

}  // namespace polarview
