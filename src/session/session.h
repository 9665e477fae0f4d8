// The viewer without its window: the settings the panels and commands edit, the status it
// publishes for them each frame, the notices, the command queue, the document, the surface cache
// and the analysis panels' data (pole inspector, spectrum, colour statistics), and what each frame
// does with them apart from drawing. The session is the one owner of all of these: the document
// and the cache return results, which it applies to the status, the notices and (a refused level
// reverts, the path field follows the model) the settings. The window application (app/viewer_app.h) owns one Session,
// runs ImGui and mirrors the surfaces on the GPU. No GL, ImGui or GLFW: tests drive a Session
// without a display (tests/session/).
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/background_job.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_measures.h"
#include "pipeline/model.h"
#include "pipeline/surface_build.h"
#include "session/command_queue.h"
#include "session/document.h"
#include "session/surface_cache.h"
#include "session/notices.h"
#include "session/viewer_settings.h"
#include "session/viewer_status.h"

namespace polarview {

// What only the window can do for a command (session/command_table.h): the rest of what commands
// do acts on the session's state and document directly.
class WindowServices {
 public:
  virtual ~WindowServices() = default;
  virtual void frameModel() = 0;  // fits the model into the views as laid out now
  virtual void setClipboard(const std::string& text) = 0;
  virtual std::string clipboard() = 0;
  virtual void takeScreenshot() = 0;
};

struct SessionOptions {
  size_t faceBudget = kDefaultFaceBudget;
  bool prepareNextLevel = true;  // make the active view's next level ahead while idle
  bool persistRecent = true;     // keep recent files in ~/.config/polarview/recent.txt
};

class Session {
 public:
  Session(const SessionOptions& options, WindowServices& window);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // What the user asked for: commands and panels edit it.
  ViewerSettings& settings() { return settings_; }
  const ViewerSettings& settings() const { return settings_; }
  // What the session reports (panels read it const); the window adds its part (GPU, frame time,
  // screenshots, picks).
  ViewerStatus& status() { return status_; }
  const ViewerStatus& status() const { return status_; }
  Notices& notices() { return notices_; }
  const Notices& notices() const { return notices_; }
  // Commands asked for by panels, keys and `view --do`, run by runCommands.
  CommandQueue& commandQueue() { return commandQueue_; }
  void queueCommand(std::string_view text) { commandQueue_.push(text); }
  // Shows what a document operation reports: its notice, the File panel's path, the file and edit
  // status.
  // Returns whether the operation did what it was asked (DocumentResult::ok).
  bool apply(DocumentResult result);
  Document& document() { return document_; }
  const Document& document() const { return document_; }
  SurfaceCache& surfaces() { return surfaces_; }
  const SurfaceCache& surfaces() const { return surfaces_; }
  const Model& model() const { return document_.model(); }

  // Finished loads and exports, then the surfaces (SurfaceCache::update): this frame's cost of
  // positions-only updates when points moved (the window adds its upload and records it).
  std::optional<EditCost> updateModelAndSurfaces();
  // The panels' derived data: pole inspector, spectrum, colour range and histogram, edit state.
  void updatePanels();
  // True while a file loads, an export runs, a refinement runs or a view waits for one.
  bool busy() const;
  // Clears a notice Notices::kLifetime after it appeared (a newer one restarts the clock).
  void expireNotice() { notices_.expire(); }
  // The automatic colour range and histogram of what the views show now.
  void updateColourRange();

  // What only the window does (the commands' clipboard, framing and screenshots).
  WindowServices& window() { return window_; }
  // Measures the active view's shown surface in the background (area, volume; status().measures).
  void startMeasure();
  // The surface the active view shows (what the exports write); nullptr before its first.
  const BuiltSurface* activeSurface() const;

 private:
  void collectColourSamples();
  void updateSpectrum();
  void updatePoleInspector();
  void updateMeasures();
  void updatePoleZoom();
  void raiseLevelsForZoom(const std::vector<int>& shortViews, int needed);
  SurfaceRequest surfaceRequest() const { return polarview::surfaceRequest(settings_, document_.model()); }

  WindowServices& window_;
  ViewerSettings settings_;
  ViewerStatus status_;
  Notices notices_;
  CommandQueue commandQueue_;
  Document document_;
  SurfaceCache surfaces_;
  // Colour statistics: the samples of the shown views by area, and what they were taken of.
  uint64_t colourRangeSignature_ = 0;
  std::vector<double> colourValues_, colourWeights_;
  ColourInterval histogramRange_{0.0, 0.0};
  int poleZoomChecked_ = -1;  // the zoom ring the views' levels were last checked for
  // The pole inspector's job: what it computes, what the panel shows, the model its pole list is of.
  BackgroundJob<std::vector<PoleInspection>> inspectJob_;
  std::string inspectRunning_, inspectShown_;
  uint64_t inspectPolesOf_ = 0;
  // The measure job (surface.measure) and what it measures ("C2PS level 3").
  BackgroundJob<SurfaceMeasures> measureJob_;
  std::string measured_;
  bool measurePending_ = false;  // asked for before the active view showed a surface
};

}  // namespace polarview
