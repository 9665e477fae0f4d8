// A rectangle of the window (x right, y down, in window coordinates) and how near a control vertex a
// click must be to pick it: shared by the panels' layout and the GL-free picking (vertex_edit.h).
#pragma once

namespace polarview {

struct ScreenRect {
  float x = 0, y = 0, w = 0, h = 0;
  bool contains(float px, float py) const { return px >= x && px < x + w && py >= y && py < y + h; }
};

// How close (window pixels) a click must come to a control vertex's projection to pick it.
constexpr float kPickRadiusPixels = 8.0f;

}  // namespace polarview
