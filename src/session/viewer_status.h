// ViewerStatus: what the session and the window report to the panels: each view's surface, the
// colour samples, the model and its files, edits, the analysis panels' results, frame time. The
// session publishes it each frame (Session::updateModelAndSurfaces, updatePanels) and the window
// adds what only it knows (GPU upload and draw, frame time, screenshots, picks); panels read it
// const. What the user asked for is ViewerSettings (viewer_settings.h).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "pipeline/level_limits.h"
#include "pipeline/point_readout.h"
#include "pipeline/pole_inspection.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/shading.h"
#include "session/viewer_settings.h"

namespace polarview {

// What the app reports about one view.
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

// The shown views' curvature samples, for the automatic colour range and the bar's histogram.
struct ColourStatus {
  ColourStatistics sampled;  // pipeline/surface_build.h's statistics of the shown samples
  int oneSign() const { return sampled.oneSign(); }
  // Area-weighted distribution of K (or H) of the shown views' surfaces over the colour bar:
  // kHistogramBins bins spanning the bar (values beyond in the end bins), the largest 1.
  std::vector<float> histogram;
};
constexpr int kHistogramBins = 48;

// The model shown and its files (Document::fileStatus).
struct FileStatus {
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

// Live editing of the base control mesh and the files written from it (Document::editStatus; the
// window adds the hovered vertex).
struct EditStatus {
  int selectedVertex = -1;          // the picked control vertex (-1: none)
  glm::dvec3 selectedPosition{0.0};
  int hoveredVertex = -1;           // the vertex a click would pick now (-1: none)
  bool dragging = false;            // a drag that started on a vertex is moving it
  int undoSteps = 0, redoSteps = 0;
  std::string undoLabel, redoLabel; // "move vertex 12", "reset"
  int movedVertices = 0;            // vertices away from their loaded position
  // Where Save and the exports write when EditSettings leaves the path empty.
  std::string defaultSavePath, defaultSurfacePath, defaultRefinedObjPath;
  std::string error;                // the last failed save or export, one line
  std::string exporting;            // what a background export is writing ("" when none)
  // Cost of the last positions-only update of the views (every view together, ms): the
  // refinement's positions, patch extraction (with pole markers), upload, and all of it.
  double positionsMs = 0.0, patchesMs = 0.0, uploadMs = 0.0, totalMs = 0.0;
  int updatedViews = 0;
};

// The surface point last read (Alt+click, double-click): panel "Point".
struct ReadoutStatus {
  bool valid = false;
  int view = 0;
  PointReadout readout;
  std::string text;  // readout.text(), what Copy puts on the clipboard
};

// The Spectrum panel's lines: one per eigenvalue ("k  lambda  block  mode"), for `linesValence`.
struct SpectrumStatus {
  std::vector<std::string> lines;
  int linesValence = 0;
};

// The pole inspector's results, computed in the background while the section is open
// (pipeline/pole_inspection.h).
struct PoleInspectorStatus {
  std::vector<Index> poles;                 // the model's pole vertices
  PoleSurvey survey;                        // and why the vertices that look polar are not (no poles: the panel says)
  std::vector<PoleInspection> inspections;  // one per distinct scheme of the visible views
  bool computing = false;
  std::string error;
};

// The active view's surface measured (command surface.measure; pipeline/surface_measures.h).
struct MeasureStatus {
  bool computing = false;
  // "C2PS level 3: area 16.699 (± 8e-06), volume 4.7666 (± 5e-14), centroid (0, 0, 0.437)"; empty: none yet
  std::string text;
};

struct ViewerStatus {
  std::array<ViewStatus, kMaxViews> views{};
  ColourStatus colour;
  FileStatus file;
  EditStatus edit;
  ReadoutStatus readout;
  SpectrumStatus spectrum;
  PoleInspectorStatus poleInspector;
  MeasureStatus measures;
  std::string lastScreenshot;  // the last file a screenshot wrote
  double frameMs = 0.0;        // CPU wall time of the last frame (to swap, GL finished)
  std::string glInfo;          // GL_VERSION / GL_RENDERER
};

}  // namespace polarview
