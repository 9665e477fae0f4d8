#include "app/viewer_styles.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "ui/viewer_panels.h"

namespace polarview {
namespace {

struct ViewStyle {
  ShadingParams::Mode mode;
  DisplayFlags display;
};

bool sameStyle(const ViewStyle& a, const ViewStyle& b) {
  const DisplayFlags &x = a.display, &y = b.display;
  return a.mode == b.mode && x.surface == y.surface && x.controlNet == y.controlNet &&
         x.patchBoundaries == y.patchBoundaries && x.poleMarkers == y.poleMarkers && x.wireframe == y.wireframe &&
         x.boundaryColor == y.boundaryColor;
}

bool isCurvature(ShadingParams::Mode mode) {
  return mode == ShadingParams::Mode::Gaussian || mode == ShadingParams::Mode::Mean;
}

}  // namespace

RgbaImage renderStyledImage(ViewerApp& app, int width, int height, int supersample, bool transparent) {
  ViewerState& state = app.state();
  // The distinct styles, a curvature map's first: its pass computes the colour range the others'
  // colour bars show (the app keeps the last range while no curvature map is shaded).
  std::vector<ViewStyle> styles;
  std::vector<size_t> styleOf(size_t(state.viewCount));
  for (int v = 0; v < state.viewCount; ++v) {
    const ViewStyle style{state.viewShade(v), state.viewDisplay(v)};
    auto found = std::find_if(styles.begin(), styles.end(), [&](const ViewStyle& s) { return sameStyle(s, style); });
    if (found == styles.end()) {
      styles.push_back(style);
      found = styles.end() - 1;
    }
    styleOf[size_t(v)] = size_t(found - styles.begin());
  }
  auto curvatureStyle = std::find_if(styles.begin(), styles.end(), [](const ViewStyle& s) {
    return isCurvature(s.mode) && s.display.surface;
  });
  if (curvatureStyle != styles.end() && curvatureStyle != styles.begin()) {
    const size_t first = size_t(curvatureStyle - styles.begin());
    std::swap(styles[0], styles[first]);
    for (size_t& s : styleOf) s = s == 0 ? first : s == first ? 0 : s;
  }

  // The shared style comes back however the passes end.
  struct Restore {
    ViewerState& state;
    ViewStyle saved;
    ~Restore() {
      state.shading.mode = saved.mode;
      state.display = saved.display;
    }
  } restore{state, {state.shading.mode, state.display}};
  std::vector<RgbaImage> images;
  for (const ViewStyle& style : styles) {
    state.shading.mode = style.mode;
    state.display = style.display;
    app.waitUntilIdle();  // takes the colour range in a curvature style
    images.push_back(app.renderImage(width, height, supersample, transparent));
  }

  // Each view's rectangle (at output size; the supersampled layout rounds within a pixel of it)
  // from the image of its style.
  RgbaImage image = std::move(images[0]);
  const std::vector<ScreenRect> rects =
      layoutViews(state.viewCount, ScreenRect{0, 0, float(width), float(height)}, colourBarReserve(state, 1.0f));
  for (int v = 0; v < state.viewCount; ++v)
    if (styleOf[size_t(v)] != 0) copyImageRect(image, images[styleOf[size_t(v)]], rects[size_t(v)]);
  return image;
}

void copyImageRect(RgbaImage& into, const RgbaImage& from, const ScreenRect& rect) {
  const int x0 = std::clamp(int(rect.x), 0, into.width), x1 = std::clamp(int(rect.x + rect.w), x0, into.width);
  const int y0 = std::clamp(int(rect.y), 0, into.height), y1 = std::clamp(int(rect.y + rect.h), y0, into.height);
  for (int y = y0; y < y1; ++y)
    std::memcpy(into.pixels.data() + 4 * (size_t(y) * size_t(into.width) + size_t(x0)),
                from.pixels.data() + 4 * (size_t(y) * size_t(from.width) + size_t(x0)), 4 * size_t(x1 - x0));
}

}  // namespace polarview
