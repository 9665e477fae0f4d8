// Images whose views differ in style (shading mode, what is drawn): `render --shade a,b,...` and
// `figure`. The app draws all views in the one style of ViewerState::shading / display; this renders
// one image per distinct style and takes each view's rectangle from the image of its own style.
#pragma once

#include "app/viewer_app.h"

namespace polarview {

// The views of `app` (refined: call after waitUntilIdle) at width x height, as renderImage draws
// them, each in its ViewSettings::shade / display (unset: the shared one). The colour range is the
// one the curvature style's samples give; labels and the strip under the views (line legend above
// the colour bar) are those of the first style. Leaves the shared style as it found it. Throws
// std::runtime_error as renderImage does. [one renderImage per distinct style]
RgbaImage renderStyledImage(ViewerApp& app, int width, int height, int supersample, bool transparent);

// Copies the pixels of `rect` (image coordinates, clipped to the images) from `from` into `into`,
// two images of one size: composes views rendered apart into one layout.
void copyImageRect(RgbaImage& into, const RgbaImage& from, const ScreenRect& rect);

}  // namespace polarview
