// Images whose views differ in style (shading mode, what is drawn): `render --shade a,b,...` and
// `figure`. The app draws each view in its View::shade / display (unset: the shared style).
#pragma once

#include "app/viewer_app.h"

namespace polarview {

// The views of `app` at width x height, each in its own style, once the views are refined and the
// colour range (of the curvature map some view shows) is taken. Throws std::runtime_error as
// renderImage does. [one renderImage]
RgbaImage renderStyledImage(ViewerApp& app, int width, int height, int supersample, bool transparent);

// Copies the pixels of `rect` (image coordinates, clipped to the images) from `from` into `into`,
// two images of one size: composes views rendered apart into one layout.
void copyImageRect(RgbaImage& into, const RgbaImage& from, const ScreenRect& rect);

}  // namespace polarview
