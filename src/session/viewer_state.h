// ViewerState: everything the viewer's panels show and edit, as plain data. The panels (ui/) only
// read and write this struct and queue commands (session/command_table.h); the app turns changes
// into refinement jobs and GPU uploads, and writes back status (refining, patch counts, timings,
// errors).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/point_readout.h"
#include "pipeline/pole_inspection.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/shading.h"
#include "pipeline/orbit_camera.h"
#include "pipeline/level_limits.h"

namespace polarview {

constexpr int kMaxViews = 4;

// What the app reports about one view (read-only for panels).
struct ViewStatus {
  bool refining = false;           // a refinement job is running for this view
  double refiningSeconds = 0.0;    // how long it has run
  bool hasSurface = false;         // some refinement is shown
  SchemeChoice shownScheme = SchemeChoice::C2PS;
  int shownLevel = 0;
  int patchCount = 0;
  std::array<int, kPatchKindCount> patchesPerKind{};
  int controlFaces = 0;            // faces of the shown level's control mesh
  double refineMs = 0.0;           // building the shown result: all of it (off the GL thread), of which
  double refineOnlyMs = 0.0;       //   refinement (made, or stepped from the view's kept one),
  double patchesMs = 0.0;          //   patch set (extracted, or assembled from cached levels),
  double samplesMs = 0.0;          //   curvature samples for the colour range;
  double uploadMs = 0.0;           // then packing + upload on the GL thread,
  int keptPatches = 0;             //   where this many patches stayed on the GPU (a level step)
  bool unparked = false;           //   shown again from the view's parked surface (a scheme toggle back)
  bool reshown = false;            //   the level shown before the last step, shown again (nothing built)
  int zoomRing = -1;               // >= 0: the view shows rings zoomRing.. of a pole, zoomed (Poles panel)
  int patchLevel = 0;              // the level the shown patches close the poles at (>= shownLevel:
                                   //   RTS/BPS close them deeper, pipeline/level_limits.h kNonC2CapLevel)
  int drawnLevel = 0;              // the level drawn (< patchLevel where deeper rings are below a pixel)
  int drawnPatches = 0;            // and its patches
  // What the last frame drew of them (pipeline/draw_selection.h): primitives (a group of sub-pixel
  // ring sectors is one), the patches they cover, and the patches outside the view (culled).
  int drawnPrimitives = 0;
  int visiblePatches = 0;
  int culledPatches = 0;
  double drawMs = 0.0;             // the view's draw, finished (PatchRenderer DrawStats::wallMilliseconds)
  int polesByScheme = 0;           // polar configurations the shown scheme refines
  int polesByCatmullClark = 0;     // those Catmull-Clark refines instead (RTS / BPS below valence 5)
  std::string fallbackReason;      // why (empty when none)
  std::string message;             // e.g. "level 8 refused: ..." (empty when all is well)
  int deepestLevel = kMaxLevel;    // deepest level of the view's scheme on this model (face budget)
  std::string levelLimit;          // the refusal a level one deeper gets (empty at kMaxLevel)
};

// One view: what it shows (its settings, which panels, keys and commands edit) and what the
// session reports about it (its status).
struct View {
  SchemeChoice scheme = SchemeChoice::C2PS;
  int level = 3;
  OrbitCamera camera;  // used when the cameras are not linked
  // Per-view styles of `render --shade a,b` and `figure` (the viewer leaves them unset): this view's
  // shading mode and what it draws instead of ViewerState::shading.mode / display, and a caption in
  // place of its title ("(c) C2PS · 4"). The app draws each view in its own style.
  std::optional<ShadingParams::Mode> shade;
  std::optional<DisplayFlags> display;
  std::string caption;
  ViewStatus status;  // written by the session and the window each frame; read-only for panels
};

inline View viewOf(SchemeChoice scheme) {
  View view;
  view.scheme = scheme;
  return view;
}

// The colour range shared by all views.
struct ColourRangeSettings {
  // Automatic: +-max(-P10, P90) of K or H by area over the shown patches without end caps (see
  // weightedSymmetricRange), percentiles of the signed value rather than of |value|, and low ones.
  // Why: a tight corner (the default mushroom's cap rim and stem bottom, with its valence-3
  // extraordinary vertices) covers a few percent of the area with |K| ten times the cap's; the
  // former 98th percentile of |K| (6.6 there) put the whole cap in the one green of "about zero".
  // With P10/P90 (2.5) the cap reads green to yellow and such tails saturate red or blue, as in
  // the paper's Fig. 13 ("larger blue or red areas result from saturation in normalization").
  // When all values have one sign (a sphere: K > 0 everywhere) the automatic range is one-sided,
  // [P10, P90] over the half of the map of that sign: +-P90 painted a sphere one red.
  bool automatic = true;
  float quantile = 0.90f;    // upper percentile P (the lower one is 1 - P)
  // Not symmetric: min and max apart; zero stays the map's middle (two slopes) when it lies between.
  bool symmetric = true;
  double typedRange = 1.0;   // typed and symmetric: [-typedRange, typedRange]
  ColourInterval typedApart; // typed, min and max apart (min < max)
  // Written by the session from the shown samples (pipeline/surface_build.h).
  ColourStatistics sampled;
  int oneSign() const { return sampled.oneSign(); }
  // The automatic range: one-sided [P(1 - P), P(P)] for one-signed values, else symmetric or each
  // side apart (a side without values keeps a sliver, 1e-3, of the other).
  ColourInterval automaticInterval() const;
  // Area-weighted distribution of K (or H) of the shown views' surfaces over the colour bar:
  // kHistogramBins bins spanning the bar (values beyond in the end bins), the largest 1.
  std::vector<float> histogram;
};
constexpr int kHistogramBins = 48;

struct FileSettings {
  std::string pathField;                 // the path text field
  std::vector<std::string> recent;       // most recent first
  std::string modelName;                 // shown model ("default: ..." or a path)
  std::string loadedPath;                // empty for the built-in default model
  std::string error;                     // last load error (the model stays)
  bool loading = false;                  // a file is being read and checked in the background
  std::string loadingPath;               // which one
  std::vector<std::string> warnings;     // non-fatal findings of the last load
  int modelVertices = 0, modelFaces = 0;
  std::string previousModelName;         // what Ctrl+Z returns to (empty: nothing to undo)
  std::vector<std::string> playlist;     // files dropped together; PageDown / PageUp step through
  int playlistIndex = -1;                // the entry last opened from it
};

struct ScreenshotSettings {
  int supersample = 1;       // 1, 2 or 4
  bool transparent = false;  // alpha 0 background
  std::string lastPath;      // last written file
};

// Live editing of the base control mesh, saving it, and exports of what a view shows. The app
// writes the read-only parts; the panel edits the paths.
struct EditSettings {
  int selectedVertex = -1;          // the picked control vertex (-1: none)
  glm::dvec3 selectedPosition{0.0};
  int hoveredVertex = -1;           // the vertex a click would pick now (-1: none)
  bool dragging = false;            // a drag that started on a vertex is moving it
  int undoSteps = 0, redoSteps = 0;
  std::string undoLabel, redoLabel; // "move vertex 12", "reset"
  int movedVertices = 0;            // vertices away from their loaded position
  // Output paths; empty means the default beside it (written by the app): <model>_edited.obj,
  // <model>_<scheme>_<level>.<surfaceFormat> and <model>_<scheme>_<level>_refined.obj next to the model file,
  // or in the current directory for the built-in model.
  std::string savePath, defaultSavePath;
  std::string surfacePath, defaultSurfacePath;  // Export surface: the format from the extension
  std::string surfaceFormat = "bv";             // surface_export.h's format name: the default path's extension
  std::string refinedObjPath, defaultRefinedObjPath;
  std::string error;                // the last failed save or export, one line
  std::string exporting;            // what a background export is writing ("" when none)
  // Cost of the last positions-only update of the views (every view together, ms): the
  // refinement's positions, patch extraction (with pole markers), upload, and all of it.
  double positionsMs = 0.0, patchesMs = 0.0, uploadMs = 0.0, totalMs = 0.0;
  int updatedViews = 0;
};

// The surface point last read (Alt+click, double-click): panel "Point".
struct ReadoutSettings {
  bool valid = false;
  int view = 0;
  PointReadout readout;
  std::string text;  // readout.text(), what Copy puts on the clipboard
};

// The Spectrum panel (paper Table 1, Fig. 1): RTS's leading eigenvalues at a valence, and one
// eigenvector v_k shown as the model (its net over the characteristic map, pipeline/eigen_nets.h).
struct SpectrumSettings {
  bool open = false;      // marked by the panel each frame it is drawn
  int valence = 6;
  int k = 3;              // the eigenvector to show (0..7)
  int c2psSteps = 0;      // > 0: that many C2PS steps first, magnified back (Fig. 1 d-f, Lemma 5)
  // Set by the app: one line per eigenvalue ("k  lambda  block  mode"), for `linesValence`.
  std::vector<std::string> lines;
  int linesValence = 0;
};

// The pole inspector (panel "Poles"): the paper's claim made visible, computed by the app in the
// background while the section is open (pipeline/pole_inspection.h).
struct PoleInspectorSettings {
  bool open = false;  // the section is open: the app keeps `inspections` up to date
  int pole = 0;       // index into `poles`
  int ring = 4;       // ring m whose K around the pole is plotted
  bool openRequested = false;  // the section opens (and scrolls into view) next frame (command poles.inspect)
  int scrollFrames = 0;  // > 0: the panel scrolls the section into view (so many frames: results grow it)
  // Pole zoom (Figs. 8, 9): >= 0: every view draws rings zoomRing .. zoomRing + 2 of the pole,
  // scaled by 2^zoomRing about it (pipeline zoomAboutPole); -1: off.
  int zoomRing = -1;
  // Set by the app.
  std::vector<Index> poles;                 // the model's pole vertices
  PoleSurvey survey;                        // and why the vertices that look polar are not (no poles: the panel says)
  std::vector<PoleInspection> inspections;  // one per distinct scheme of the visible views
  bool computing = false;
  std::string error;
};

struct ViewerState {
  int viewCount = 1;
  // New views start on different schemes: the point of several views is comparing them.
  std::array<View, kMaxViews> views{viewOf(SchemeChoice::C2PS), viewOf(SchemeChoice::RTS),
                                            viewOf(SchemeChoice::BPS), viewOf(SchemeChoice::CatmullClark)};
  int activeView = 0;          // the view hotkeys (0-9, scheme) apply to; last one hovered/clicked
  bool linkCameras = true;     // all views use sharedCamera
  bool linkLevels = true;      // the level slider and keys 0-9 set every view's level
  OrbitCamera sharedCamera;

  ShadingParams shading;
  DisplayFlags display;
  ColourRangeSettings colour;
  FileSettings file;
  ScreenshotSettings screenshot;
  EditSettings edit;
  PoleInspectorSettings poleInspector;
  ReadoutSettings readout;
  SpectrumSettings spectrum;
  // Commands asked for by panels, keys and `view --do`, as text ("level 7", "camera.frame":
  // session/command_table.h), run in order by the app once a frame.
  std::vector<std::string> queuedCommands;

  bool showPanels = true;      // Tab
  bool showHelp = false;       // ?
  bool showStats = true;
  double frameMs = 0.0;        // CPU wall time of the last frame (to swap, GL finished)
  std::string glInfo;          // GL_VERSION / GL_RENDERER
  std::string notice;          // last message for the user (screenshot path, camera copied, ...)

  // The camera view `v` draws with.
  OrbitCamera& camera(int v) { return linkCameras ? sharedCamera : views[v].camera; }
  const OrbitCamera& camera(int v) const { return linkCameras ? sharedCamera : views[v].camera; }
  // The colour range every view uses now (automatic or typed).
  ColourInterval colourInterval() const {
    if (colour.automatic) return colour.automaticInterval();
    return colour.symmetric ? ColourInterval::symmetric(colour.typedRange) : colour.typedApart;
  }
  // View v's shading mode and what it draws (its own style, or the shared one).
  ShadingParams::Mode viewShade(int v) const { return views[size_t(v)].shade.value_or(shading.mode); }
  const DisplayFlags& viewDisplay(int v) const {
    return views[size_t(v)].display ? *views[size_t(v)].display : display;
  }
  // The curvature map (Gaussian or mean) a visible surface is shaded with, if any: the first view's
  // that has one (one image holds one colour bar).
  std::optional<ShadingParams::Mode> curvatureShade() const {
    return firstSurfaceShade([](ShadingParams::Mode m) { return shadingModeInfo(m).curvature; });
  }
  // The light lines (highlight or reflection) a visible surface shows, if any: they get a legend.
  std::optional<ShadingParams::Mode> lineShade() const {
    return firstSurfaceShade([](ShadingParams::Mode m) { return shadingModeInfo(m).lightLines; });
  }
  // True when a view shows a curvature map (then the colour bar is shown).
  bool showsColourBar() const { return curvatureShade().has_value(); }

 private:
  template <class Predicate>
  std::optional<ShadingParams::Mode> firstSurfaceShade(Predicate wanted) const {
    for (int v = 0; v < viewCount; ++v)
      if (viewDisplay(v).surface && wanted(viewShade(v))) return viewShade(v);
    return std::nullopt;
  }
};

// What the colour range does when it is not the paper's zero-centred map, e.g. "all K > 0: range
// 0.8 .. 1.2, one-sided"; empty otherwise.
std::string colourRangeNote(const ViewerState& state);
// Automatic colour range on or off; switching it off keeps the current range (typed = automatic).
void setAutomaticRange(ViewerState& state, bool automatic);
// Sets the level of the active view (or every view when levels are linked); levels above the
// view's deepest level leave the state unchanged and set a notice.
void requestLevel(ViewerState& state, int level);
// Every view's projection (linked or not), so side-by-side views stay comparable.
void setOrthographic(ViewerState& state, bool orthographic);
// The next (step 1) or previous (-1) scheme for `view`.
void cycleScheme(ViewerState& state, int view, int step);

}  // namespace polarview
