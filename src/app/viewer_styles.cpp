#include "app/viewer_styles.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "ui/viewer_panels.h"

namespace polarview {

RgbaImage renderStyledImage(ViewerApp& app, int width, int height, int supersample, bool transparent) {
  app.waitUntilIdle();  // the colour range of the curvature style some view shows
  return app.renderImage(width, height, supersample, transparent);
}

void copyImageRect(RgbaImage& into, const RgbaImage& from, const ScreenRect& rect) {
  const int x0 = std::clamp(int(rect.x), 0, into.width), x1 = std::clamp(int(rect.x + rect.w), x0, into.width);
  const int y0 = std::clamp(int(rect.y), 0, into.height), y1 = std::clamp(int(rect.y + rect.h), y0, into.height);
  for (int y = y0; y < y1; ++y)
    std::memcpy(into.pixels.data() + 4 * (size_t(y) * size_t(into.width) + size_t(x0)),
                from.pixels.data() + 4 * (size_t(y) * size_t(from.width) + size_t(x0)), 4 * size_t(x1 - x0));
}

}  // namespace polarview
