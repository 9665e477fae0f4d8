// Level of detail: the shallowest level of a feature-adaptive surface that draws the same picture
// as its level L to within a pixel. Levels past the first differ only near the features (poles,
// extraordinary vertices), inside the cap or end caps that close level m there, whose size s_m
// halves a level; once s_m projects below a pixel at every feature, deeper levels add sub-pixel
// rings only (C2PS level 12 at the default view: 246,237 patches, most far below a pixel).
// GL-free: the viewer draws levelToDraw's set, refines and reports level L (docs/shading.md).
#pragma once

#include <vector>

#include "core/spline/patch.h"
#include "pipeline/orbit_camera.h"

namespace polarview {

struct DetailSizes {
  // Per level 0..L: the largest patch of that level (world length: a B-spline patch's face edges,
  // a cap's or end cap's extent), which bounds the cap or end caps closing that level at a feature.
  std::vector<double> levelSize;
  // Where the finest level's patches are (one point per occupied cell of a grid of about their
  // size): the features, whose distance to the eye sets the scale.
  std::vector<Point> features;
};

// The sizes of a patch set (a surface's patches of levels 0..L). [O(patches)]
DetailSizes detailSizes(const std::vector<Patch>& patches);

// The smallest level m <= `level` whose caps or end caps (what differs from level L's set: about two
// of its patches across) project below `pixels` across at every feature in front of the camera
// (perspective: at its depth; orthographic: the view's scale), for a view `viewportHeight` pixels
// high; `level` when no level is that small or the eye is at a feature.
// [O(features + levels)]
int levelToDraw(const DetailSizes& sizes, int level, const OrbitCamera& camera, double viewportHeight,
                double pixels = 3.0);

}  // namespace polarview
