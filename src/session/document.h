// The viewer's document: the model every view refines and where it came from (a file, the default
// model, a conversion), the edits of its control points with their undo history, the model
// replaced last (Ctrl+Z), the dropped-files playlist, recent files, and the files written from it
// (the edited mesh, .bv and refined-mesh exports). Loads and exports run in the background; the
// model stays until a new one is ready. Its operations return what the viewer should show (a
// DocumentResult: a notice, the File panel's path); its own facts (the file, the edits) it reports
// as FileStatus and EditStatus. No GL, no viewer state: tested without a display.
#pragma once

#include <filesystem>
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
#include "session/notices.h"
#include "session/viewer_settings.h"
#include "session/viewer_status.h"

namespace polarview {

// What Export writes of the active view: its limit surface (.bv and the other formats of
// surface_export.h) or its control mesh refined uniformly to its level (OBJ).
enum class SurfaceExport { LimitSurface, RefinedMesh };

// ~/.config/polarview/recent.txt (empty without $HOME): the recent files; the window keeps its
// layout beside it.
std::string recentFilePath();

// What a document operation has to tell the viewer: whether it did it, a notice for the user, and
// the path the File panel's field names from now on (a file asked for, or the model shown's file).
// The session applies it (Session::apply).
struct [[nodiscard]] DocumentResult {
  bool ok = true;
  std::optional<Notice> notice;
  std::optional<std::string> pathField;
  // This result followed by `later` (later's notice and path win where it has them).
  DocumentResult& then(DocumentResult later);
};

class Document {
 public:
  // `faceBudget`: one view's, which bounds the exports; `persistRecent`: keep recent files in
  // ~/.config/polarview/recent.txt.
  Document(size_t faceBudget, bool persistRecent);
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

  // The model's file, name, load state, playlist and recent files.
  const FileStatus& fileStatus() const { return file_; }

  // Loads an OBJ now (blocks), named `name` (default: its path); on failure the message goes to
  // fileStatus().error, the model stays (not ok).
  DocumentResult loadFile(const std::string& path, const std::string& name = "");
  // Reads and checks an OBJ on a worker thread (pollLoad takes it); a request while one runs
  // replaces any queued one: the last request wins.
  DocumentResult requestLoad(const std::string& path);
  bool loading() const { return loadJob_.running(); }
  DocumentResult pollLoad();
  // A drop of files: loads the first, keeps all as the playlist.
  DocumentResult dropFiles(int count, const char* const* paths);
  DocumentResult openPlaylistEntry(int index);  // wraps around
  // Shows `mesh` (validated here; not ok, with the error in fileStatus().error, when it is not usable).
  DocumentResult loadMesh(PolyMesh mesh, const std::string& name, const std::string& path = "");
  // assets/default.obj, or the generated mushroom when the asset is missing.
  DocumentResult loadDefaultModel();
  DocumentResult reloadModel();
  // Shows the model replaced last (Open, Default model, a drop); again to redo.
  DocumentResult undoModelReplacement();
  // Ctrl+Z: the last vertex drag, or with none left the model replacement.
  DocumentResult undo();
  DocumentResult redo() { return redoEdit(); }
  DocumentResult resetEdits();
  // The editor's points become the model's (same faces, new points revision): the views follow
  // with positions-only updates.
  void commitEditedPoints();
  // Paper Fig. 14: the extraordinary vertices made polar configurations (a new model; Ctrl+Z returns).
  DocumentResult convertToPolar(bool pentagons);
  // Faces of 5 or more sides made triangle fans around their centroids, so that n-gon caps (a
  // cylinder's) become poles (a new model; Ctrl+Z returns).
  DocumentResult convertToFans();
  // The Spectrum panel's eigenvector net as the model.
  DocumentResult showEigenvector(const SpectrumSettings& spectrum);
  // The recent files kept in recentFilePath().
  void loadRecent();

  // Ctrl+S: the edited mesh as OBJ (atomic; a failure leaves no file and shows one line): a model
  // read from a file is written into the file's text as loaded, only moved vertices' coordinates
  // replaced (obj_io.h saveObjEdited); a generated one as plain v/f lines. To `paths.savePath`, or
  // the default one beside the model.
  DocumentResult saveEditedMesh(const EditSettings& paths);
  // What `shown` (the active view's surface; `settings` name the view and the output paths) is, as
  // its limit surface or its refined control mesh, written on a worker thread (pollExport takes the
  // result).
  DocumentResult startExport(SurfaceExport what, const BuiltSurface* shown, const ViewerSettings& settings);
  bool exporting() const { return exportJob_.running(); }
  DocumentResult pollExport();
  // The edit part of the status: selection, history, the last failed save or export, the running
  // export, the last positions-only update's cost and the default output paths (named after
  // `shown`, the active view's surface, or its settings before it shows one). The window's part
  // (the hovered vertex) stays as it is.
  void reportEdit(const BuiltSurface* shown, const ViewerSettings& settings, EditStatus& status) const;

  // Every positions-only update since the model was loaded (the last 10000), and recording one.
  const std::vector<EditCost>& editCosts() const { return editCosts_; }
  void recordEditCost(const EditCost& cost);

 private:
  // An export job started (its path), or refused before starting (why).
  struct ExportStart {
    std::string path, error;
  };
  ExportStart startSurfaceExport(const SurfaceKey& shown, const EditSettings& paths);
  ExportStart startRefinedMeshExport(const SurfaceKey& shown, const EditSettings& paths);
  // Shows `model` as the next model generation (what Ctrl+Z returns to is the one shown now).
  DocumentResult adoptModel(Model model, const std::string& path);
  DocumentResult loadFailed(const std::string& path, const std::string& error);
  // A failed save or export: the edit panel's error line and the same as an error notice.
  DocumentResult editFailed(std::string message);
  DocumentResult undoEdit();
  DocumentResult redoEdit();
  void rememberRecent(const std::string& path);
  // Where the default outputs go (beside the model file, or the current directory for the built-in
  // model) and what they are named after.
  std::filesystem::path outputFolder() const;
  std::string outputStem() const;
  std::string defaultSavePath() const;
  std::string defaultSurfacePath(SchemeChoice scheme, int level, const std::string& format) const;

  size_t faceBudget_;
  bool persistRecent_;
  Model model_;
  Model previousModel_;       // the model before the last replacement (Ctrl+Z)
  std::string previousPath_;  // its file (empty for generated models)
  glm::dvec3 modelMin_{-1.0}, modelMax_{1.0};
  ControlMeshEditor editor_;
  int movedVertices_ = 0;  // editor_.movedVertexCount(), counted when points change
  std::vector<EditCost> editCosts_;
  EditCost lastEditCost_;  // the last one recorded (kept across models, as the panel shows it)
  FileStatus file_;
  std::string editError_;  // the last failed save or export, one line
  BackgroundJob<LoadedModel> loadJob_;
  std::optional<std::string> queuedLoad_;
  BackgroundJob<std::string> exportJob_;  // the notice to show when done; throws on failure
  std::string exportTarget_;
};

}  // namespace polarview
