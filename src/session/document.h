// The viewer's document: the model every view refines and where it came from (a file, the default
// model, a conversion), the edits of its control points with their undo history, the model
// replaced last (Ctrl+Z), the dropped-files playlist, recent files, and the files written from it
// (the edited mesh, .bv and refined-mesh exports). Loads and exports run in the background; the
// model stays until a new one is ready. Reports to the panels through ViewerState (file, edit,
// notice). No GL: tested without a display.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "pipeline/model.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"
#include "pipeline/vertex_edit.h"
#include "pipeline/background_job.h"
#include "session/surface_cache.h"
#include "session/viewer_state.h"

namespace polarview {

// What Export writes of the active view: its limit surface (.bv and the other formats of
// surface_export.h) or its control mesh refined uniformly to its level (OBJ).
enum class SurfaceExport { LimitSurface, RefinedMesh };

// ~/.config/polarview/recent.txt (empty without $HOME): the recent files; the window keeps its
// layout beside it.
std::string recentFilePath();

class Document {
 public:
  // `faceBudget`: one view's, which bounds the exports; `persistRecent`: keep recent files in
  // ~/.config/polarview/recent.txt.
  Document(ViewerState& state, size_t faceBudget, bool persistRecent);
  ~Document();  // waits for a running load or export
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  // Called whenever another model replaces the shown one (load, conversion, Ctrl+Z): the views
  // re-frame it and forget the old model's failures.
  std::function<void()> onModelReplaced;

  const Model& model() const { return model_; }
  // Bounding box of the model's control points.
  glm::dvec3 modelMin() const { return modelMin_; }
  glm::dvec3 modelMax() const { return modelMax_; }
  const ControlMeshEditor& editor() const { return editor_; }
  ControlMeshEditor& editor() { return editor_; }

  // Loads an OBJ now (blocks), named `name` (default: its path); on failure the message goes to
  // state.file.error, the model stays.
  bool loadFile(const std::string& path, const std::string& name = "");
  // Reads and checks an OBJ on a worker thread (pollLoad takes it); a request while one runs
  // replaces any queued one: the last request wins.
  void requestLoad(const std::string& path);
  bool loading() const { return loadJob_.running(); }
  void pollLoad();
  // A drop of files: loads the first, keeps all as the playlist.
  void dropFiles(int count, const char* const* paths);
  void openPlaylistEntry(int index);  // wraps around
  // Shows `mesh` (validated here; false with the error in the state when it is not usable).
  bool loadMesh(PolyMesh mesh, const std::string& name, const std::string& path = "");
  // assets/default.obj, or the generated mushroom when the asset is missing.
  void loadDefaultModel();
  void reloadModel();
  // Shows the model replaced last (Open, Default model, a drop); again to redo.
  void undoModelReplacement();
  // Ctrl+Z: the last vertex drag, or with none left the model replacement.
  void undo();
  void redo() { redoEdit(); }
  void resetEdits();
  // The editor's points become the model's (same faces, new points revision): the views follow
  // with positions-only updates.
  void commitEditedPoints();
  // Paper Fig. 14: the extraordinary vertices made polar configurations (a new model; Ctrl+Z returns).
  void convertToPolar(bool pentagons);
  // Faces of 5 or more sides made triangle fans around their centroids, so that n-gon caps (a
  // cylinder's) become poles (a new model; Ctrl+Z returns).
  void convertToFans();
  // The Spectrum panel's eigenvector net as the model.
  void showEigenvector();
  void loadRecent();

  // Ctrl+S: the edited mesh as OBJ (atomic; a failure leaves no file and shows one line): a model
  // read from a file is written into the file's text as loaded, only moved vertices' coordinates
  // replaced (obj_io.h saveObjEdited); a generated one as plain v/f lines.
  void saveEditedMesh();
  // What `shown` (the active view's surface) is, as its limit surface or its refined control mesh,
  // written on a worker thread (pollExport takes the result).
  void startExport(SurfaceExport what, const BuiltSurface* shown);
  bool exporting() const { return exportJob_.running(); }
  void pollExport();
  // state.edit: selection, history, default output paths (named after `shown`, the active view's).
  void updateEditState(const BuiltSurface* shown);

  // Every positions-only update since the model was loaded (the last 10000), and recording one.
  const std::vector<EditCost>& editCosts() const { return editCosts_; }
  void recordEditCost(const EditCost& cost);

 private:
  // Shows `model` as the next model generation (what Ctrl+Z returns to is the one shown now).
  void adoptModel(Model model, const std::string& path);
  void loadFailed(const std::string& path, const std::string& error);
  void undoEdit();
  void redoEdit();
  void rememberRecent(const std::string& path);

  ViewerState& state_;
  size_t faceBudget_;
  bool persistRecent_;
  Model model_;
  Model previousModel_;       // the model before the last replacement (Ctrl+Z)
  std::string previousPath_;  // its file (empty for generated models)
  glm::dvec3 modelMin_{-1.0}, modelMax_{1.0};
  ControlMeshEditor editor_;
  int movedVertices_ = 0;  // editor_.movedVertexCount(), counted when points change
  std::vector<EditCost> editCosts_;
  BackgroundJob<LoadedModel> loadJob_;
  std::optional<std::string> queuedLoad_;
  BackgroundJob<std::string> exportJob_;  // the notice to show when done; throws on failure
  std::string exportTarget_;
};

}  // namespace polarview
