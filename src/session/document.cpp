// The viewer's document (document.h): the model and where it came from, edits, files and exports.
#include "session/document.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/mesh/ev_to_polar.h"
#include "core/mesh/ngon_to_fan.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/shapes.h"
#include "core/subdiv/refiner.h"
#include "core/subdiv/table_pool.h"
#include "pipeline/eigen_nets.h"
#include "pipeline/memory_budget.h"
#include "pipeline/patch_export.h"
#include "pipeline/surface_export.h"
#include "pipeline/model.h"
#include "pipeline/level_limits.h"
#include "pipeline/surface_build.h"

namespace polarview {
namespace {

constexpr size_t kMaxRecentFiles = 10;
constexpr size_t kMaxEditCosts = 10000;


// A message for the one-line error field: line breaks become spaces.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

std::string absolutePath(const std::string& path) {
  std::error_code ignored;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ignored);
  return absolute.empty() ? path : absolute.lexically_normal().string();
}

std::string defaultModelAsset() { return std::string(POLARVIEW_ASSET_DIR) + "/default.obj"; }

}  // namespace

std::string recentFilePath() {
  const char* home = std::getenv("HOME");
  if (!home || !*home) return {};
  return std::string(home) + "/.config/polarview/recent.txt";
}

Document::Document(ViewerState& state, size_t faceBudget, bool persistRecent)
    : state_(state), faceBudget_(faceBudget), persistRecent_(persistRecent) {}

Document::~Document() {
  loadJob_.join();
  exportJob_.join();
}

void Document::recordEditCost(const EditCost& cost) {
  if (editCosts_.size() >= kMaxEditCosts) editCosts_.erase(editCosts_.begin());
  editCosts_.push_back(cost);
  state_.edit.positionsMs = cost.positionsMs;
  state_.edit.patchesMs = cost.patchesMs;
  state_.edit.uploadMs = cost.uploadMs;
  state_.edit.totalMs = cost.totalMs;
  state_.edit.updatedViews = cost.views;
}

bool Document::loadFile(const std::string& path, const std::string& name) {
  state_.file.pathField = path;
  LoadedModel loaded = readModelFile(path);
  if (!loaded.error.empty()) {
    loadFailed(path, loaded.error);
    return false;
  }
  if (!name.empty()) loaded.model.name = name;
  adoptModel(std::move(loaded.model), path);
  state_.file.warnings = std::move(loaded.warnings);
  return true;
}

void Document::requestLoad(const std::string& path) {
  state_.file.pathField = path;
  if (loadJob_.running()) {
    queuedLoad_ = path;  // started when the running one is done; its result is then dropped
    return;
  }
  state_.file.loading = true;
  state_.file.loadingPath = path;
  loadJob_.start([path] { return readModelFile(path); });
}

void Document::pollLoad() {
  std::optional<LoadedModel> done = loadJob_.poll();  // readModelFile never throws
  if (!done) return;
  LoadedModel loaded = std::move(*done);
  state_.file.loading = false;
  state_.file.loadingPath.clear();
  if (queuedLoad_) {
    std::string next = std::move(*queuedLoad_);
    queuedLoad_.reset();
    requestLoad(next);
    return;
  }
  if (!loaded.error.empty()) {
    loadFailed(loaded.path, loaded.error);
    return;
  }
  adoptModel(std::move(loaded.model), loaded.path);
  state_.file.warnings = std::move(loaded.warnings);
  state_.notice = "opened " + loaded.path;
}

void Document::loadFailed(const std::string& path, const std::string& error) {
  state_.file.error = error;
  state_.notice = "could not open " + path + " (the current model stays)";
}

void Document::dropFiles(int count, const char* const* paths) {
  if (count < 1 || !paths || !paths[0]) return;
  if (count > 1) {
    // Several files: open the first, keep all of them as a list to step through.
    state_.file.playlist.clear();
    for (int i = 0; i < count; ++i)
      if (paths[i]) state_.file.playlist.emplace_back(paths[i]);
    state_.file.playlistIndex = 0;
    state_.notice = "opening the first of " + std::to_string(count) + " dropped files (PageDown / PageUp for the others)";
  }
  requestLoad(paths[0]);
}

void Document::openPlaylistEntry(int index) {
  const std::vector<std::string>& list = state_.file.playlist;
  if (list.empty()) return;
  index = (index % int(list.size()) + int(list.size())) % int(list.size());
  state_.file.playlistIndex = index;
  requestLoad(list[size_t(index)]);
}

void Document::undoModelReplacement() {
  if (!previousModel_.mesh) {
    state_.notice = "nothing to undo";
    return;
  }
  // Swap back (a second Ctrl+Z redoes): the previous model is shown as a new model generation,
  // with its analysis (the faces are the same: nothing to analyse again).
  Model previous = previousModel_;
  previous.points = 0;
  const std::string previousPath = previousPath_;
  adoptModel(std::move(previous), previousPath);
  state_.notice = "back to " + model_.name;
}

bool Document::loadMesh(PolyMesh mesh, const std::string& name, const std::string& path) {
  Model model = makeModel(std::make_shared<const PolyMesh>(std::move(mesh)), name, 0);  // checked by its analysis
  if (std::string error = checkModel(model); !error.empty()) {
    state_.file.error = error;
    return false;
  }
  adoptModel(std::move(model), path);
  return true;
}

void Document::adoptModel(Model model, const std::string& path) {
  const PolyMesh& mesh = *model.mesh;
  modelMin_ = modelMax_ = mesh.points.front();
  for (const Point& p : mesh.points) {
    modelMin_ = glm::min(modelMin_, p);
    modelMax_ = glm::max(modelMax_, p);
  }
  state_.file.modelVertices = mesh.vertexCount();
  state_.file.modelFaces = mesh.faceCount();
  model.generation = model_.generation + 1;
  if (model_.mesh) {  // what Ctrl+Z returns to
    previousModel_ = model_;
    previousPath_ = state_.file.loadedPath;
    state_.file.previousModelName = model_.name;
  }
  model_ = std::move(model);
  const std::string& name = model_.name;
  // Editing starts over: the loaded points are what Reset returns to.
  editor_.start(model_.mesh->points);
  movedVertices_ = 0;
  editCosts_.clear();
  state_.edit.error.clear();
  state_.file.modelName = name;
  state_.file.loadedPath = path;
  if (!path.empty()) state_.file.pathField = path;  // the field names what is shown (after Ctrl+Z too)
  state_.file.error.clear();
  state_.file.warnings.clear();
  if (!path.empty()) rememberRecent(path);
  if (onModelReplaced) onModelReplaced();
}

void Document::loadDefaultModel() {
  std::string asset = std::string(POLARVIEW_ASSET_DIR) + "/default.obj";
  // Named as the default model from the start, so Ctrl+Z back to it still names it so (outputs
  // default_edited.obj, not model_edited.obj).
  if (std::filesystem::exists(asset) && loadFile(asset, "default: " + asset)) return;
  loadMesh(shapes::mushroom(12), "default: mushroom (generated, n = 12)");
}

void Document::rememberRecent(const std::string& path) {
  std::vector<std::string>& recent = state_.file.recent;
  std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
  recent.erase(std::remove(recent.begin(), recent.end(), absolute), recent.end());
  recent.insert(recent.begin(), absolute);
  if (recent.size() > kMaxRecentFiles) recent.resize(kMaxRecentFiles);
  if (!persistRecent_) return;
  std::string file = recentFilePath();
  if (file.empty()) return;
  std::error_code ignored;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ignored);
  std::ofstream out(file);
  for (const std::string& p : recent) out << p << '\n';
}

void Document::loadRecent() {
  std::ifstream in(recentFilePath());
  std::string line;
  while (std::getline(in, line) && state_.file.recent.size() < kMaxRecentFiles) {
    if (!line.empty()) state_.file.recent.push_back(line);
  }
}

void Document::undo() {
  // Ctrl+Z undoes vertex drags first; with none left it goes back to the previous model.
  if (editor_.undoCount() > 0) undoEdit();
  else undoModelReplacement();
}

void Document::reloadModel() {
  if (state_.file.loadedPath.empty()) loadDefaultModel();
  else requestLoad(state_.file.loadedPath);
}

void Document::showEigenvector() {
  const SpectrumSettings& spectrum = state_.spectrum;
  try {
    const std::string name = "RTS eigenvector v" + std::to_string(spectrum.k) + ", valence " + std::to_string(spectrum.valence) +
                             (spectrum.c2psSteps > 0 ? ", " + std::to_string(spectrum.c2psSteps) + " C2PS steps" : "");
    if (loadMesh(eigenNet(spectrum.valence, spectrum.k, spectrum.c2psSteps), name, "")) state_.notice = name + " (Ctrl+Z returns)";
  } catch (const std::exception& e) {
    state_.notice = std::string("eigenvector: ") + e.what();
  }
}

void Document::convertToPolar(bool pentagons) {
  if (!model_.mesh) return;
  try {
    PolarConversion conversion = convertExtraordinaryToPolar(*model_.mesh, pentagons, model_.name);
    if (conversion.converted.empty()) {
      state_.notice = "no extraordinary vertex to convert (interior, all quads around it, valence != 4)";
      return;
    }
    const size_t count = conversion.converted.size();
    const std::string name = "converted (Fig. 14" + std::string(pentagons ? "c" : "a") + "): " + model_.name;
    if (loadMesh(std::move(conversion.mesh), name, ""))
      state_.notice = std::to_string(count) + " extraordinary vertices made poles (Ctrl+Z returns)";
  } catch (const std::exception& e) {
    state_.notice = std::string("conversion failed: ") + e.what();
  }
}

void Document::convertToFans() {
  if (!model_.mesh) return;
  FanConversion conversion = convertNgonsToFans(*model_.mesh);
  if (conversion.faces.empty()) {
    state_.notice = "no face with " + std::to_string(kMinFanSides) + " or more sides to make a triangle fan";
    return;
  }
  const size_t count = conversion.faces.size();
  if (loadMesh(std::move(conversion.mesh), "triangle fans: " + model_.name, ""))
    state_.notice = std::to_string(count) + (count == 1 ? " face" : " faces") + " made triangle fans (Ctrl+Z returns)";
}

void Document::commitEditedPoints() {
  if (!model_.mesh || editor_.points().size() != model_.mesh->points.size()) return;
  // A new mesh object (a background job may still read the old one), the same faces.
  auto mesh = std::make_shared<PolyMesh>(*model_.mesh);
  mesh->points = editor_.points();
  modelMin_ = modelMax_ = mesh->points.front();
  for (const Point& p : mesh->points) {
    modelMin_ = glm::min(modelMin_, p);
    modelMax_ = glm::max(modelMax_, p);
  }
  model_.mesh = std::move(mesh);
  ++model_.points;
  movedVertices_ = editor_.movedVertexCount();
}

void Document::undoEdit() {
  const std::string what = editor_.undoLabel();
  if (!editor_.undo()) {
    state_.notice = "nothing to undo";
    return;
  }
  commitEditedPoints();
  state_.notice = "undone: " + what;
}

void Document::redoEdit() {
  const std::string what = editor_.redoLabel();
  if (!editor_.redo()) {
    state_.notice = "nothing to redo";
    return;
  }
  commitEditedPoints();
  state_.notice = "redone: " + what;
}

void Document::resetEdits() {
  if (!editor_.resetToLoaded()) {
    state_.notice = "no control vertex has moved";
    return;
  }
  commitEditedPoints();
  state_.notice = "every control vertex is back where the file had it (Ctrl+Z undoes the reset)";
}

void Document::saveEditedMesh() {
  if (!model_.mesh) return;
  // A save before the panels' first update (view --do edit.save) still has its default path.
  if (state_.edit.defaultSavePath.empty()) updateEditState(nullptr);
  const std::string path = state_.edit.savePath.empty() ? state_.edit.defaultSavePath : state_.edit.savePath;
  bool keptSource = false;
  try {
    // Atomic: a failure leaves no file. A conversion's model has no source text (other faces).
    if (model_.sourceText) keptSource = saveObjEdited(path, *model_.mesh, *model_.sourceText, model_.name);
    else saveObj(path, *model_.mesh, model_.name);
  } catch (const std::exception& e) {
    state_.edit.error = oneLine(std::string("could not save: ") + e.what());
    state_.notice = state_.edit.error;
    return;
  }
  state_.edit.error.clear();
  state_.notice = "saved the edited mesh to " + absolutePath(path) + " (" + std::to_string(movedVertices_) +
                  (movedVertices_ == 1 ? " vertex" : " vertices") + " moved" +
                  (keptSource ? "; every other line as in the file" : "") + ")";
}

void Document::startExport(SurfaceExport what, const BuiltSurface* shown) {
  if (!model_.mesh) return;
  if (exportJob_.running()) {
    state_.notice = "still writing " + exportTarget_;
    return;
  }
  // What the active view shows: its scheme and level, on the model's current points.
  const int v = std::clamp(state_.activeView, 0, state_.viewCount - 1);
  if (!shown || shown->key.model != model_.generation) {
    state_.edit.error = "view " + std::to_string(v + 1) + " shows no surface of this model yet";
    state_.notice = state_.edit.error;
    return;
  }
  const SchemeChoice scheme = shown->key.scheme;
  const int level = shown->key.level;
  const RefineOptions options = refineOptionsFor(scheme, level);
  const Model model = model_;  // the mesh is immutable: the worker keeps this version
  std::string path;
  if (what == SurfaceExport::LimitSurface) {
    path = state_.edit.surfacePath.empty() ? state_.edit.defaultSurfacePath : state_.edit.surfacePath;
    // The format from the file's extension, as `polarview export` chooses it.
    const ExportFormat* format = exportFormatForPath(path);
    if (!format) {
      state_.edit.error = "cannot tell the format of " + path + ": name it " + exportFormatExtensions();
      state_.notice = state_.edit.error;
      return;
    }
    ExportSettings settings;
    settings.source = model.name;
    settings.schemeLabel = schemeChoiceLabel(scheme);
    settings.level = level;
    // The view's own refinement path and limit (the shown level is within it).
    const RefineRequest request{options, false, 0, faceBudget_};
    exportJob_.start([model, request, path, scheme, level, format, settings] {
      const PatchSet set = makePatchSet(*model.mesh, model.name, request);
      const std::string summary = exportSummary(writeSurfaceFile(path, set, *format, settings));
      return "wrote " + absolutePath(path) + ": " + summary + " (" + schemeChoiceLabel(scheme) + " level " +
             std::to_string(level) + ", feature-adaptive)";
    });
  } else {
    path = state_.edit.refinedObjPath.empty() ? state_.edit.defaultRefinedObjPath : state_.edit.refinedObjPath;
    // Uniform refinement: every face x4 a level (x2 where RTS/BPS refine radially); refused at once
    // when its estimate exceeds what a view may take.
    const size_t budget = faceBudget_ * kBytesPerAdaptiveFace / kBytesPerUniformFace;
    const bool radial = model.radialForRtsBps && (options.scheme == Scheme::RTS || options.scheme == Scheme::BPS);
    const UniformLevelEstimate estimate = estimateUniformLevel(*model.mesh, options, radial, budget);
    if (!estimate.fits) {
      state_.edit.error = std::string("refined control mesh refused: ") + schemeChoiceLabel(scheme) + " level " +
                          std::to_string(level) + " would have about " + std::to_string(estimate.faces) +
                          " faces, over the budget of " + std::to_string(budget) + " (level " +
                          std::to_string(estimate.deepestFitting) + " fits)";
      state_.notice = state_.edit.error;
      return;
    }
    exportJob_.start([model, options, path, budget, scheme, level] {
      std::string done;
      {
        const PolyMesh refined = makeRefinedMesh(*model.mesh, model.name, {options, true, 0, budget});  // as `refine`
        saveObj(path, refined, model.name);
        done = "wrote " + absolutePath(path) + ": the " + schemeChoiceLabel(scheme) + " level " + std::to_string(level) +
               " control mesh (" + std::to_string(refined.faceCount()) + " faces, " +
               std::to_string(refined.vertexCount()) + " vertices)";
      }
      // The refinement's tables went to the pool (up to half the RAM): a viewer keeps none idle.
      clearTablePool();
      return done;
    });
  }
  exportTarget_ = path;
  state_.notice = "writing " + path + "...";
}

void Document::pollExport() {
  if (!exportJob_.finished()) return;
  try {
    state_.notice = *exportJob_.poll();
    state_.edit.error.clear();
  } catch (const std::exception& e) {
    // Bad levels, a full disk, an unwritable folder: the atomic writers left nothing behind.
    state_.edit.error = oneLine(std::string("could not write ") + exportTarget_ + ": " + e.what());
    state_.notice = state_.edit.error;
  }
  exportTarget_.clear();
}

void Document::updateEditState(const BuiltSurface* shown) {
  EditSettings& edit = state_.edit;
  edit.selectedVertex = editor_.selected();
  if (edit.selectedVertex >= 0) edit.selectedPosition = editor_.points()[size_t(edit.selectedVertex)];
  edit.dragging = editor_.dragging();
  edit.undoSteps = int(editor_.undoCount());
  edit.redoSteps = int(editor_.redoCount());
  edit.undoLabel = editor_.undoLabel();
  edit.redoLabel = editor_.redoLabel();
  edit.movedVertices = movedVertices_;
  edit.exporting = exportJob_.running() ? exportTarget_ : std::string();

  // Default outputs: beside the model file, or in the current directory for the built-in model.
  namespace fs = std::filesystem;
  const std::string& loaded = state_.file.loadedPath;
  const bool builtIn = loaded.empty() || loaded == defaultModelAsset();
  const fs::path folder = builtIn ? fs::path() : fs::path(loaded).parent_path();
  // The file's own name (the built-in model opened by its path too: "default"), else a generated one's.
  const std::string stem = !loaded.empty() ? fs::path(loaded).stem().string()
                                           : (state_.file.modelName.rfind("default", 0) == 0 ? "default" : "model");
  edit.defaultSavePath = (folder / (stem + "_edited.obj")).string();
  // The exports write what the active view shows (its settings until it shows something).
  const int v = std::clamp(state_.activeView, 0, state_.viewCount - 1);
  const SchemeChoice scheme = shown ? shown->key.scheme : state_.views[size_t(v)].scheme;
  const int level = shown ? shown->key.level : state_.views[size_t(v)].level;
  const std::string tag = std::string("_") + schemeChoiceCliName(scheme) + "_" + std::to_string(level);
  const ExportFormat* format = exportFormatNamed(edit.surfaceFormat);
  edit.defaultSurfacePath = (folder / (stem + tag + (format ? format->extensions.front() : ".bv"))).string();
  edit.defaultRefinedObjPath = (folder / (stem + tag + "_refined.obj")).string();
}

}  // namespace polarview
