// The readout of a picked surface point (pipeline/point_readout.h).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/mesh/obj_io.h"
#include "core/spline/patch_extraction.h"
#include "core/subdiv/adaptive_refiner.h"
#include "pipeline/point_readout.h"

namespace polarview {

TEST_CASE("point readout: a point picked on any kind of patch reads back that patch's (u, v), K, H and principal curvatures") {
  const PolyMesh mesh = loadObj(std::string(POLARVIEW_ASSET_DIR) + "/default.obj");
  for (Scheme scheme : {Scheme::C2PS, Scheme::CatmullClark}) {
    const PatchSet set = extractPatches(AdaptiveRefinement(mesh, RefineOptions{scheme, 3, false}));
    int checked[5] = {0, 0, 0, 0, 0};
    for (size_t k = 0; k < set.patches.size(); k += 7) {
      const Patch& patch = set.patches[k];
      if (checked[int(patch.kind)] >= 6) continue;
      const double u = 0.3 + 0.01 * double(k % 20), v = 0.6 - 0.01 * double(k % 13);
      const SurfacePoint truth = evaluatePatch(patch, u, v);
      // As a depth read-back gives it: on the surface up to a little, along the normal.
      const Point picked = truth.position + 1e-7 * truth.normal;
      const auto readout = readSurfacePoint(set.patches, picked, 1e-4);
      CAPTURE(k);
      REQUIRE(readout);
      CHECK(readout->distance <= 1.01e-7);
      // Interior parameters: the point belongs to this patch alone.
      CHECK(readout->patchIndex == k);
      CHECK(readout->u == doctest::Approx(u).epsilon(1e-5));
      CHECK(readout->v == doctest::Approx(v).epsilon(1e-5));
      CHECK(readout->point.gaussian == doctest::Approx(truth.gaussian).epsilon(1e-4));
      CHECK(readout->point.mean == doctest::Approx(truth.mean).epsilon(1e-4));
      // k1 k2 = K and (k1 + k2) / 2 = H.
      CHECK(readout->k1 * readout->k2 == doctest::Approx(readout->point.gaussian).epsilon(1e-9));
      CHECK(0.5 * (readout->k1 + readout->k2) == doctest::Approx(readout->point.mean).epsilon(1e-9));
      CHECK(readout->kind == patch.kind);
      CHECK(readout->text().find("K ") != std::string::npos);
      ++checked[int(patch.kind)];
    }
    CHECK(checked[int(PatchKind::Regular)] > 0);
    if (scheme == Scheme::C2PS) {
      CHECK(checked[int(PatchKind::PolarRing)] > 0);
      CHECK(checked[int(PatchKind::PoleCap)] > 0);
    } else {
      CHECK(checked[int(PatchKind::EndCap)] > 0);
    }
  }
  // Nothing near: no readout.
  const PatchSet set = extractPatches(AdaptiveRefinement(mesh, RefineOptions{Scheme::C2PS, 1, false}));
  CHECK_FALSE(readSurfacePoint(set.patches, Point(100.0, 0.0, 0.0), 1e-3));
}

}  // namespace polarview
