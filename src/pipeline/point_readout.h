// What the surface is at a point the user picked (the viewer's readout, Alt+click or
// double-click): the patch that holds the point nearest a picked world position, and its
// differential geometry there. Plain data, no GL.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/spline/patch.h"

namespace polarview {

struct PointReadout {
  size_t patchIndex = 0;
  double u = 0.0, v = 0.0;      // the patch's parameters of the point
  double distance = 0.0;        // from the picked position to the surface point
  SurfacePoint point;           // position, derivatives, normal, K, H
  double k1 = 0.0, k2 = 0.0;    // principal curvatures H +- sqrt(H^2 - K), k1 >= k2
  PatchKind kind = PatchKind::Regular;
  int level = 0, ring = -1, pole = -1;
  // Several lines: what the panel shows and Copy puts on the clipboard.
  std::string text() const;
};

// The surface point of `patches` nearest `picked` (a depth read-back: on the surface up to the
// depth buffer's resolution): patches whose control box, grown by `tolerance`, holds it are searched
// (a grid of starts, then Newton steps on |X(u, v) - picked|^2). nullopt when none is that close.
// [O(patches) + O(candidates)]
std::optional<PointReadout> readSurfacePoint(const std::vector<Patch>& patches, const Point& picked, double tolerance);

}  // namespace polarview
