// The viewer's ImGui panels, on-screen overlay (view labels, colour bar) and input handling.
// They edit the ViewerSettings, show the ViewerStatus (const) and queue commands: no GL calls, no
// GPU objects.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/screen_rect.h"
#include "session/command_table.h"
#include "session/notices.h"
#include "session/viewer_settings.h"
#include "session/viewer_status.h"

struct ImDrawList;
struct ImFont;

namespace polarview {

// What the panels work with: the settings they edit, the status they show, the notices (the
// latest is shown; a refused level posts one) and the queue their buttons add commands to.
struct PanelContext {
  ViewerSettings& settings;
  const ViewerStatus& status;
  Notices& notices;
  CommandQueue& commands;
};

// A view's title: "C2PS · 3", or "RTS · 3 · poles by CC (valence < 5)" when the scheme left its
// poles to Catmull-Clark (RTS and BPS need valence >= 5).
std::string viewTitle(const ViewStatus& status);
// Height of the strip at the top of each view that its title covers (framing keeps the model below).
float viewTitleHeight(float scale);
// Width of the panel column on the left of the window (0 when the panels are hidden).
float panelColumnWidth(const ViewerSettings& settings);
// Height kept free under the views for the colour bar (curvature modes) or the line legend
// (highlight / reflection lines); 0 for lit shading.
float colourBarReserve(const ViewerSettings& settings, float scale);
// `count` views side by side in `frame` (a full grid such as 2 x 2 when that makes each view clearly
// larger), above a strip of `bottomReserve`. [O(count)]
std::vector<ScreenRect> layoutViews(int count, const ScreenRect& frame, float bottomReserve);

// A button that queues command `id`, labelled from the command table ("Frame model (F)"); an id
// that is no row of the table throws (session/command_ids.h names those the panels use).
void commandButton(CommandQueue& commands, std::string_view id);
// The "Poles" section: pole list, K and H at the pole per scheme shown, the rings' approach to it
// (log scale) and K around ring m (pole_inspector_panel.cpp). Marks the inspector open.
void drawPoleInspectorPanel(PanelContext& ui);
// The "Spectrum (Fig. 1)" section: RTS's eigenvalues at a valence, and a button that shows an
// eigenvector's net as the model (pole_inspector_panel.cpp). Marks the section open.
void drawSpectrumPanel(PanelContext& ui);

// All panels (file, views, display, shading, colour, camera, screenshot, stats) and the help
// window. Call between ImGui::NewFrame and ImGui::Render.
void drawViewerPanels(PanelContext& ui);

// A visible pole of one view, in the overlay's coordinates (the app projects the poles and drops
// those the surface hides).
struct PoleMarker {
  float x = 0, y = 0;
};


// A control vertex marked in the overlay: the selected one (filled) or the one a click would pick
// (a ring), in the overlay's coordinates.
struct VertexMarker {
  float x = 0, y = 0;
  bool selected = false;
};

// The surface point the Point panel reads (Alt+click), in the overlay's coordinates.
struct PointMarker {
  float x = 0, y = 0;
};

// View labels ("C2PS · 3"), refining / loading indicators, pole rings, marked control vertices, the
// picked surface point, and
// the colour bar with numeric ticks (curvature modes) or a legend of the light lines (highlight /
// reflection modes), drawn into `list` (the background list on screen, a private list for
// screenshots). `scale` multiplies sizes (supersampled screenshots).
void drawViewOverlay(ImDrawList* list, ImFont* font, const ViewerSettings& settings, const ViewerStatus& status,
                     const std::vector<ScreenRect>& views,
                     const ScreenRect& frame, float scale, const std::vector<PoleMarker>& poles = {},
                     const std::vector<VertexMarker>& vertices = {}, const std::vector<PointMarker>& points = {});

// The one-line legend of highlight / reflection lines: light direction, spacing and width, e.g.
// "highlight lines: light (1, 0, 0), spacing 0.25 x model radius, dark 30%"; empty in other modes.
std::string lineLegend(const ShadingParams& shading);

// A double-click on a view (the app reads the depth there and sets the pivot), or the wheel over it
// (zoomNotches != 0: the app zooms towards the surface point there, or the target's plane).
struct PivotPick {
  int view = 0;
  float x = 0, y = 0;  // window coordinates
  float zoomNotches = 0.0f;
  bool readout = false;     // also read the surface point there (ViewerStatus::readout)
  bool movePivot = true;    // false: the readout only (Alt+click)
};

// A left drag that began on a control vertex: where the cursor is now (window coordinates), for the
// app to move the vertex; `released` on the frame the button comes up (the drag ends there).
struct VertexDragEvent {
  int view = 0;
  float x = 0, y = 0;
  bool released = false;
};

// What the mouse asked for this frame beyond the camera moves handle() makes itself.
struct InputResult {
  std::optional<PivotPick> pivot;            // double-click or wheel: the app reads the depth there
  std::optional<VertexDragEvent> vertexDrag;  // a control vertex being dragged
  bool deselect = false;                      // a click (no drag) on a view away from any vertex
  int hoveredView = -1;                       // the view under the cursor, -1 over panels or outside
};

// Asked on a plain left press in view `view` at (x, y) while the control net is shown: true when
// it picked a control vertex there (the drag then edits it instead of orbiting).
using VertexPicker = std::function<bool(int view, float x, float y)>;

// Hotkeys (queued as the command table's commands) and mouse camera control. Keys are ignored while ImGui wants the keyboard and the mouse
// while it wants the mouse (io.WantCaptureKeyboard / WantCaptureMouse). Keeps which view a drag
// started in, so a drag that crosses into another view keeps turning the first one.
class ViewerInput {
 public:
  // Call after ImGui::NewFrame. A left press on a control vertex (pickVertex says so) starts a
  // vertex drag; elsewhere left drags orbit as always.
  InputResult handle(PanelContext& ui, const std::vector<ScreenRect>& views, const VertexPicker& pickVertex = {});
  // A key press from the window's key callback (GLFW key and modifier bits); handle() applies the
  // presses queued since the last frame, so none is lost however short or slow the frame.
  void queueKeyPress(int key, int mods) { pendingKeys_.emplace_back(key, mods); }

 private:
  int dragView_ = -1;
  bool vertexDrag_ = false;    // the left drag in dragView_ moves a control vertex
  bool pressedOnEmpty_ = false;  // the left press hit no vertex (a release without drag deselects)
  std::vector<std::pair<int, int>> pendingKeys_;
};

// Wheel over a view where no surface is under the cursor: zooms towards the point of the camera
// target's plane under it (OrbitCamera::zoomAt).
void zoomTowardsCursor(ViewerSettings& settings, const ScreenRect& view, int v, float notches);


}  // namespace polarview
