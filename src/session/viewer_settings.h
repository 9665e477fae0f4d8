// ViewerSettings: what the user asked the viewer for (views, schemes, levels, cameras, shading,
// colour range, file and output paths, the analysis panels' choices). Only commands
// (session/command_table.h) and panels (ui/) edit it; the session applies its rules to it (a
// refused level reverts, a pole zoom raises levels). What the session and the window report back
// is ViewerStatus (viewer_status.h).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "pipeline/orbit_camera.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/shading.h"

namespace polarview {

constexpr int kMaxViews = 4;

// One view: its scheme and level, its camera and, for `render` and `figure`, its own style.
struct View {
  SchemeChoice scheme = SchemeChoice::C2PS;
  int level = 3;
  OrbitCamera camera;  // used when the cameras are not linked
  // Per-view styles of `render --shade a,b` and `figure` (the viewer leaves them unset): this view's
  // shading mode and what it draws instead of ViewerSettings::shading.mode / display, and a caption in
  // place of its title ("(c) C2PS · 4"). The app draws each view in its own style.
  std::optional<ShadingParams::Mode> shade;
  std::optional<DisplayFlags> display;
  std::string caption;
};

inline View viewOf(SchemeChoice scheme) {
  View view;
  view.scheme = scheme;
  return view;
}

// The colour range shared by all views: automatic (from the shown samples, ViewerStatus::colour)
// or typed.
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
};

struct FileSettings {
  std::string pathField;  // the path text field (a load asked for or a model shown names its file here)
};

struct ScreenshotSettings {
  int supersample = 1;       // 1, 2 or 4
  bool transparent = false;  // alpha 0 background
};

// Where Save and the exports write; empty means the default beside the model (EditStatus's
// default paths): <model>_edited.obj, <model>_<scheme>_<level>.<surfaceFormat> and
// <model>_<scheme>_<level>_refined.obj next to the model file, or in the current directory for the
// built-in model.
struct EditSettings {
  std::string savePath;
  std::string surfacePath;           // Export surface: the format from the extension
  std::string surfaceFormat = "bv";  // surface_export.h's format name: the default path's extension
  std::string refinedObjPath;
};

// The Spectrum panel (paper Table 1, Fig. 1): RTS's leading eigenvalues at a valence, and one
// eigenvector v_k shown as the model (its net over the characteristic map, pipeline/eigen_nets.h).
struct SpectrumSettings {
  bool open = false;      // marked by the panel each frame it is drawn (the session takes the mark)
  int valence = 6;
  int k = 3;              // the eigenvector to show (0..7)
  int c2psSteps = 0;      // > 0: that many C2PS steps first, magnified back (Fig. 1 d-f, Lemma 5)
};

// The pole inspector (panel "Poles"): which pole and ring, and the pole zoom.
struct PoleInspectorSettings {
  bool open = false;  // marked by the panel each frame the section is open: the session keeps the results up to date
  int pole = 0;       // index into ViewerStatus::poleInspector.poles
  int ring = 4;       // ring m whose K around the pole is plotted
  bool openRequested = false;  // the section opens (and scrolls into view) next frame (command poles.inspect)
  int scrollFrames = 0;  // > 0: the panel scrolls the section into view (so many frames: results grow it)
  // Pole zoom (Figs. 8, 9): >= 0: every view draws rings zoomRing .. zoomRing + 2 of the pole,
  // scaled by 2^zoomRing about it (pipeline zoomAboutPole); -1: off.
  int zoomRing = -1;
};

struct ViewerSettings {
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
  SpectrumSettings spectrum;

  bool showPanels = true;      // Tab
  bool showHelp = false;       // ?
  bool showStats = true;

  // The camera view `v` draws with.
  OrbitCamera& camera(int v) { return linkCameras ? sharedCamera : views[size_t(v)].camera; }
  const OrbitCamera& camera(int v) const { return linkCameras ? sharedCamera : views[size_t(v)].camera; }
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
  // The view the exports and the level keys act on (activeView within the visible views).
  int clampedActiveView() const { return activeView < 0 ? 0 : activeView >= viewCount ? viewCount - 1 : activeView; }

 private:
  template <class Predicate>
  std::optional<ShadingParams::Mode> firstSurfaceShade(Predicate wanted) const {
    for (int v = 0; v < viewCount; ++v)
      if (viewDisplay(v).surface && wanted(viewShade(v))) return viewShade(v);
    return std::nullopt;
  }
};

// The next (step 1) or previous (-1) scheme for `view`.
void cycleScheme(ViewerSettings& settings, int view, int step);
// Every view's projection (linked or not), so side-by-side views stay comparable.
void setOrthographic(ViewerSettings& settings, bool orthographic);

}  // namespace polarview
