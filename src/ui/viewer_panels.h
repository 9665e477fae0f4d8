// The viewer's ImGui panels, on-screen overlay (view labels, colour bar) and input handling.
// They read and write a ViewerState only: no GL calls, no GPU objects.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ui/viewer_state.h"

struct ImDrawList;
struct ImFont;

namespace polarview {

// A rectangle in window coordinates (top-left origin, y down), as ImGui uses.
struct ScreenRect {
  float x = 0, y = 0, w = 0, h = 0;
  bool contains(float px, float py) const { return px >= x && px < x + w && py >= y && py < y + h; }
};

// One hotkey or mouse gesture and what it does; the help window lists them all.
struct HotkeyHelp {
  const char* keys;
  const char* action;
};
const std::vector<HotkeyHelp>& hotkeyList();

// A view's title: "C2PS · 3", or "RTS · 3 · poles by CC (valence < 5)" when the scheme left its
// poles to Catmull-Clark (RTS and BPS need valence >= 5).
std::string viewTitle(const ViewStatus& status);
// Height of the strip at the top of each view that its title covers (framing keeps the model below).
float viewTitleHeight(float scale);
// Width of the panel column on the left of the window (0 when the panels are hidden).
float panelColumnWidth(const ViewerState& state);
// Height kept free under the views for the colour bar (curvature modes) or the line legend
// (highlight / reflection lines); 0 for lit shading.
float colourBarReserve(const ViewerState& state, float scale);
// `count` views side by side in `frame` (a full grid such as 2 x 2 when that makes each view clearly
// larger), above a strip of `bottomReserve`. [O(count)]
std::vector<ScreenRect> layoutViews(int count, const ScreenRect& frame, float bottomReserve);

// All panels (file, views, display, shading, colour, camera, screenshot, stats) and the help
// window. Call between ImGui::NewFrame and ImGui::Render.
void drawViewerPanels(ViewerState& state);

// A visible pole of one view, in the overlay's coordinates (the app projects the poles and drops
// those the surface hides).
struct PoleMarker {
  float x = 0, y = 0;
};

// View labels ("C2PS · 3"), refining / loading indicators, pole rings, and the colour bar with
// numeric ticks (curvature modes) or a legend of the light lines (highlight / reflection modes),
// drawn into `list` (the background list on screen, a private list for screenshots). `scale`
// multiplies sizes (supersampled screenshots).
void drawViewOverlay(ImDrawList* list, ImFont* font, const ViewerState& state, const std::vector<ScreenRect>& views,
                     const ScreenRect& frame, float scale, const std::vector<PoleMarker>& poles = {});

// The one-line legend of highlight / reflection lines: light direction, spacing and width, e.g.
// "highlight lines: light (1, 0, 0), spacing 0.25 x model radius, dark 30%"; empty in other modes.
std::string lineLegend(const ShadingParams& shading);

// A double-click on a view (the app reads the depth there and sets the pivot), or the wheel over it
// (zoomNotches != 0: the app zooms towards the surface point there, or the target's plane).
struct PivotPick {
  int view = 0;
  float x = 0, y = 0;  // window coordinates
  float zoomNotches = 0.0f;
};

// Hotkeys and mouse camera control. Keys are ignored while ImGui wants the keyboard and the mouse
// while it wants the mouse (io.WantCaptureKeyboard / WantCaptureMouse). Keeps which view a drag
// started in, so a drag that crosses into another view keeps turning the first one.
class ViewerInput {
 public:
  // Call after ImGui::NewFrame. Returns a double-click position to resolve, if any.
  std::optional<PivotPick> handle(ViewerState& state, const std::vector<ScreenRect>& views);
  // A key press from the window's key callback (GLFW key and modifier bits); handle() applies the
  // presses queued since the last frame, so none is lost however short or slow the frame.
  void queueKeyPress(int key, int mods) { pendingKeys_.emplace_back(key, mods); }

 private:
  int dragView_ = -1;
  std::vector<std::pair<int, int>> pendingKeys_;
};

// Wheel over a view where no surface is under the cursor: zooms towards the point of the camera
// target's plane under it (OrbitCamera::zoomAt).
void zoomTowardsCursor(ViewerState& state, const ScreenRect& view, int v, float notches);

// Automatic colour range on or off; switching it off keeps the current range (typed = automatic).
void setAutomaticRange(ViewerState& state, bool automatic);

// Sets the level of the active view (or every view when levels are linked); levels above
// kMaxLevel leave the state unchanged and set a notice.
void requestLevel(ViewerState& state, int level);

}  // namespace polarview
