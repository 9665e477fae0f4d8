// The viewer's document (document.h): the model and where it came from, edits, files and exports.
#include "session/document.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/mesh/atomic_file.h"
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

// "_c2ps_4": what the default export paths add for the view's scheme and level.
std::string outputTag(SchemeChoice scheme, int level) {
  return std::string("_") + schemeChoiceCliName(scheme) + "_" + std::to_string(level);
}

}  // namespace

std::string recentFilePath() {
  const char* home = std::getenv("HOME");
  if (!home || !*home) return {};
  return std::string(home) + "/.config/polarview/recent.txt";
}

DocumentResult& DocumentResult::then(DocumentResult later) {
  ok = later.ok;
  if (later.notice) notice = std::move(later.notice);
  if (later.pathField) pathField = std::move(later.pathField);
  return *this;
}

namespace {

DocumentResult withNotice(Notice notice, bool ok = true) { return DocumentResult{ok, std::move(notice), {}}; }
DocumentResult failed() { return DocumentResult{false, {}, {}}; }

}  // namespace

Document::Document(size_t faceBudget, bool persistRecent) : faceBudget_(faceBudget), persistRecent_(persistRecent) {}

Document::~Document() {
  loadJob_.join();
  exportJob_.join();
}

void Document::recordEditCost(const EditCost& cost) {
  if (editCosts_.size() >= kMaxEditCosts) editCosts_.erase(editCosts_.begin());
  editCosts_.push_back(cost);
  lastEditCost_ = cost;
}

DocumentResult Document::loadFile(const std::string& path, const std::string& name) {
  DocumentResult result{true, {}, path};
  LoadedModel loaded = readModelFile(path);
  if (!loaded.error.empty()) return result.then(loadFailed(path, loaded.error));
  if (!name.empty()) loaded.model.name = name;
  result.then(adoptModel(std::move(loaded.model), path));
  file_.warnings = std::move(loaded.warnings);
  return result;
}

DocumentResult Document::requestLoad(const std::string& path) {
  // A file of the dropped list, however asked for (PageDown, a click on the list): the list marks it.
  const std::vector<std::string>& list = file_.playlist;
  const bool marked = file_.playlistIndex >= 0 && size_t(file_.playlistIndex) < list.size() && list[size_t(file_.playlistIndex)] == path;
  if (const auto entry = std::find(list.begin(), list.end(), path); !marked && entry != list.end())
    file_.playlistIndex = int(entry - list.begin());
  if (loadJob_.running()) {
    queuedLoad_ = path;  // started when the running one is done; its result is then dropped
  } else {
    file_.loading = true;
    file_.loadingPath = path;
    loadJob_.start([path] { return readModelFile(path); });
  }
  return DocumentResult{true, {}, path};
}

DocumentResult Document::pollLoad() {
  std::optional<LoadedModel> done = loadJob_.poll();  // readModelFile never throws
  if (!done) return {};
  LoadedModel loaded = std::move(*done);
  file_.loading = false;
  file_.loadingPath.clear();
  if (queuedLoad_) {
    std::string next = std::move(*queuedLoad_);
    queuedLoad_.reset();
    return requestLoad(next);
  }
  if (!loaded.error.empty()) return loadFailed(loaded.path, loaded.error);
  DocumentResult result = adoptModel(std::move(loaded.model), loaded.path);
  file_.warnings = std::move(loaded.warnings);
  result.notice = info("opened " + loaded.path);
  return result;
}

DocumentResult Document::loadFailed(const std::string& path, const std::string& error) {
  file_.error = error;
  return withNotice(polarview::error("could not open " + path + " (the current model stays)"), false);
}

DocumentResult Document::dropFiles(int count, const char* const* paths) {
  if (count < 1 || !paths || !paths[0]) return {};
  DocumentResult result;
  if (count > 1) {
    // Several files: open the first, keep all of them as a list to step through.
    file_.playlist.clear();
    for (int i = 0; i < count; ++i)
      if (paths[i]) file_.playlist.emplace_back(paths[i]);
    file_.playlistIndex = 0;
    result.notice = info("opening the first of " + std::to_string(count) + " dropped files (PageDown / PageUp for the others)");
  }
  return result.then(requestLoad(paths[0]));
}

DocumentResult Document::openPlaylistEntry(int index) {
  const std::vector<std::string>& list = file_.playlist;
  if (list.empty()) return {};
  index = (index % int(list.size()) + int(list.size())) % int(list.size());
  file_.playlistIndex = index;
  return requestLoad(list[size_t(index)]);
}

DocumentResult Document::undoModelReplacement() {
  if (!previousModel_.mesh) return withNotice(info("nothing to undo"));
  // Swap back (a second Ctrl+Z redoes): the previous model is shown as a new model generation,
  // with its analysis (the faces are the same: nothing to analyse again).
  Model previous = previousModel_;
  previous.points = 0;
  const std::string previousPath = previousPath_;
  DocumentResult result = adoptModel(std::move(previous), previousPath);
  result.notice = info("back to " + model_.name);
  return result;
}

DocumentResult Document::loadMesh(PolyMesh mesh, const std::string& name, const std::string& path) {
  Model model = makeModel(std::make_shared<const PolyMesh>(std::move(mesh)), name, 0);  // checked by its analysis
  if (std::string error = checkModel(model); !error.empty()) {
    file_.error = error;
    return failed();
  }
  return adoptModel(std::move(model), path);
}

DocumentResult Document::adoptModel(Model model, const std::string& path) {
  const PolyMesh& mesh = *model.mesh;
  modelMin_ = modelMax_ = mesh.points.front();
  for (const Point& p : mesh.points) {
    modelMin_ = glm::min(modelMin_, p);
    modelMax_ = glm::max(modelMax_, p);
  }
  file_.modelVertices = mesh.vertexCount();
  file_.modelFaces = mesh.faceCount();
  model.generation = model_.generation + 1;
  if (model_.mesh) {  // what Ctrl+Z returns to
    previousModel_ = model_;
    previousPath_ = file_.loadedPath;
    file_.previousModelName = model_.name;
  }
  model_ = std::move(model);
  // Editing starts over: the loaded points are what Reset returns to.
  editor_.start(model_.mesh->points);
  movedVertices_ = 0;
  editCosts_.clear();
  editError_.clear();
  file_.modelName = model_.name;
  file_.loadedPath = path;
  file_.error.clear();
  file_.warnings.clear();
  if (!path.empty()) rememberRecent(path);
  if (onModelReplaced) onModelReplaced();
  DocumentResult result;
  if (!path.empty()) result.pathField = path;  // the field names what is shown (after Ctrl+Z too)
  return result;
}

DocumentResult Document::loadDefaultModel() {
  std::string asset = defaultModelAsset();
  // Named as the default model from the start, so Ctrl+Z back to it still names it so (outputs
  // default_edited.obj, not model_edited.obj).
  if (std::filesystem::exists(asset)) {
    DocumentResult result = loadFile(asset, "default: " + asset);
    if (result.ok) return result;
  }
  return loadMesh(shapes::mushroom(12), "default: mushroom (generated, n = 12)");
}

void Document::rememberRecent(const std::string& path) {
  std::vector<std::string>& recent = file_.recent;
  std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
  recent.erase(std::remove(recent.begin(), recent.end(), absolute), recent.end());
  recent.insert(recent.begin(), absolute);
  if (recent.size() > kMaxRecentFiles) recent.resize(kMaxRecentFiles);
  if (!persistRecent_) return;
  std::string file = recentFilePath();
  if (file.empty()) return;
  std::error_code ignored;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ignored);
  std::string text;
  for (const std::string& p : recent) text += p + '\n';
  try {
    writeFileAtomically(file, text);  // two viewers at once: each list whole, never a torn one
  } catch (const std::exception&) {
    // An unwritable config folder costs the recent list only.
  }
}

void Document::loadRecent() {
  std::ifstream in(recentFilePath());
  std::string line;
  while (std::getline(in, line) && file_.recent.size() < kMaxRecentFiles) {
    if (!line.empty()) file_.recent.push_back(line);
  }
}

DocumentResult Document::undo() {
  // Ctrl+Z undoes vertex drags first; with none left it goes back to the previous model.
  if (editor_.undoCount() > 0) return undoEdit();
  return undoModelReplacement();
}

DocumentResult Document::reloadModel() {
  if (file_.loadedPath.empty()) return loadDefaultModel();
  return requestLoad(file_.loadedPath);
}

DocumentResult Document::showEigenvector(const SpectrumSettings& spectrum) {
  try {
    const std::string name = "RTS eigenvector v" + std::to_string(spectrum.k) + ", valence " + std::to_string(spectrum.valence) +
                             (spectrum.c2psSteps > 0 ? ", " + std::to_string(spectrum.c2psSteps) + " C2PS steps" : "");
    DocumentResult result = loadMesh(eigenNet(spectrum.valence, spectrum.k, spectrum.c2psSteps), name, "");
    if (result.ok) result.notice = info(name + " (Ctrl+Z returns)");
    return result;
  } catch (const std::exception& e) {
    return withNotice(error(std::string("eigenvector: ") + e.what()), false);
  }
}

DocumentResult Document::convertToPolar(bool pentagons) {
  if (!model_.mesh) return {};
  try {
    PolarConversion conversion = convertExtraordinaryToPolar(*model_.mesh, pentagons, model_.name);
    if (conversion.converted.empty())
      return withNotice(info("no extraordinary vertex to convert (interior, all quads around it, valence != 4)"));
    const size_t count = conversion.converted.size();
    const std::string name = "converted (Fig. 14" + std::string(pentagons ? "c" : "a") + "): " + model_.name;
    DocumentResult result = loadMesh(std::move(conversion.mesh), name, "");
    if (result.ok) result.notice = info(std::to_string(count) + " extraordinary vertices made poles (Ctrl+Z returns)");
    return result;
  } catch (const std::exception& e) {
    return withNotice(error(std::string("conversion failed: ") + e.what()), false);
  }
}

DocumentResult Document::convertToFans() {
  if (!model_.mesh) return {};
  FanConversion conversion = convertNgonsToFans(*model_.mesh);
  if (conversion.faces.empty())
    return withNotice(info("no face with " + std::to_string(kMinFanSides) + " or more sides to make a triangle fan"));
  const size_t count = conversion.faces.size();
  DocumentResult result = loadMesh(std::move(conversion.mesh), "triangle fans: " + model_.name, "");
  if (result.ok)
    result.notice = info(std::to_string(count) + (count == 1 ? " face" : " faces") + " made triangle fans (Ctrl+Z returns)");
  return result;
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

DocumentResult Document::undoEdit() {
  const std::string what = editor_.undoLabel();
  if (!editor_.undo()) return withNotice(info("nothing to undo"));
  commitEditedPoints();
  return withNotice(info("undone: " + what));
}

DocumentResult Document::redoEdit() {
  const std::string what = editor_.redoLabel();
  if (!editor_.redo()) return withNotice(info("nothing to redo"));
  commitEditedPoints();
  return withNotice(info("redone: " + what));
}

DocumentResult Document::resetEdits() {
  if (!editor_.resetToLoaded()) return withNotice(info("no control vertex has moved"));
  commitEditedPoints();
  return withNotice(info("every control vertex is back where the file had it (Ctrl+Z undoes the reset)"));
}

DocumentResult Document::editFailed(std::string message) {
  editError_ = std::move(message);
  return withNotice(error(editError_), false);
}

DocumentResult Document::saveEditedMesh(const EditSettings& paths) {
  if (!model_.mesh) return {};
  const std::string path = paths.savePath.empty() ? defaultSavePath() : paths.savePath;
  bool keptSource = false;
  try {
    // Atomic: a failure leaves no file. A conversion's model has no source text (other faces).
    if (model_.sourceText) keptSource = saveObjEdited(path, *model_.mesh, *model_.sourceText, model_.name);
    else saveObj(path, *model_.mesh, model_.name);
  } catch (const std::exception& e) {
    return editFailed(oneLine(std::string("could not save: ") + e.what()));
  }
  editError_.clear();
  return withNotice(info("saved the edited mesh to " + absolutePath(path) + " (" + std::to_string(movedVertices_) +
                         (movedVertices_ == 1 ? " vertex" : " vertices") + " moved" +
                         (keptSource ? "; every other line as in the file" : "") + ")"));
}

DocumentResult Document::startExport(SurfaceExport what, const BuiltSurface* shown, const ViewerSettings& settings) {
  if (!model_.mesh) return {};
  if (exportJob_.running()) return withNotice(info("still writing " + exportTarget_), false);
  // What the active view shows: its scheme and level, on the model's current points.
  if (!shown || shown->key.model != model_.generation)
    return editFailed("view " + std::to_string(settings.clampedActiveView() + 1) + " shows no surface of this model yet");
  const ExportStart start = what == SurfaceExport::LimitSurface ? startSurfaceExport(shown->key, settings.edit)
                                                                : startRefinedMeshExport(shown->key, settings.edit);
  if (!start.error.empty()) return editFailed(start.error);
  exportTarget_ = start.path;
  return withNotice(info("writing " + start.path + "..."));
}

Document::ExportStart Document::startSurfaceExport(const SurfaceKey& shown, const EditSettings& paths) {
  const SchemeChoice scheme = shown.scheme;
  const int level = shown.level;
  const std::string path =
      paths.surfacePath.empty() ? defaultSurfacePath(scheme, level, paths.surfaceFormat) : paths.surfacePath;
  // The format from the file's extension, as `polarview export` chooses it.
  const ExportFormat* format = exportFormatForPath(path);
  if (!format) return {path, "cannot tell the format of " + path + ": name it " + exportFormatExtensions()};
  ExportSettings written;
  written.source = model_.name;
  written.schemeLabel = schemeChoiceLabel(scheme);
  written.level = level;
  // The view's own refinement path and limit (the shown level is within it).
  const RefineRequest request =
      RefineRequest::withinFaces(refineOptionsFor(scheme, level), RefinePath::FeatureAdaptive, faceBudget_);
  const Model model = model_;  // the mesh is immutable: the worker keeps this version
  exportJob_.start([model, request, path, scheme, level, format, written] {
    const PatchSet set = makePatchSet(*model.mesh, model.name, request);
    const std::string summary = exportSummary(writeSurfaceFile(path, set, *format, written));
    return "wrote " + absolutePath(path) + ": " + summary + " (" + schemeChoiceLabel(scheme) + " level " +
           std::to_string(level) + ", feature-adaptive)";
  });
  return {path, {}};
}

Document::ExportStart Document::startRefinedMeshExport(const SurfaceKey& shown, const EditSettings& paths) {
  const SchemeChoice scheme = shown.scheme;
  const int level = shown.level;
  const std::string& typed = paths.refinedObjPath;
  const std::string path =
      typed.empty() ? (outputFolder() / (outputStem() + outputTag(scheme, level) + "_refined.obj")).string() : typed;
  // Uniform refinement: every face x4 a level (x2 where RTS/BPS refine radially); refused at once
  // when its estimate exceeds what a view may take.
  const RefineOptions options = refineOptionsFor(scheme, level);
  const size_t budget = faceBudget_ * kBytesPerAdaptiveFace / kBytesPerUniformFace;
  const bool radial = model_.radialForRtsBps && schemeTraits(options.scheme).keepsValence;
  const UniformLevelEstimate estimate = estimateUniformLevel(*model_.mesh, options, radial, budget);
  if (!estimate.fits)
    return {path, std::string("refined control mesh refused: ") + schemeChoiceLabel(scheme) + " level " +
                      std::to_string(level) + " would have about " + std::to_string(estimate.faces) +
                      " faces, over the budget of " + std::to_string(budget) + " (level " +
                      std::to_string(estimate.deepestFitting) + " fits)"};
  const Model model = model_;
  const RefineRequest request = RefineRequest::withinFaces(options, RefinePath::Uniform, budget);
  exportJob_.start([model, request, path, scheme, level] {
    std::string done;
    {
      const PolyMesh refined = makeRefinedMesh(*model.mesh, model.name, request);  // as `refine` writes it
      saveObj(path, refined, model.name);
      done = "wrote " + absolutePath(path) + ": the " + schemeChoiceLabel(scheme) + " level " + std::to_string(level) +
             " control mesh (" + std::to_string(refined.faceCount()) + " faces, " +
             std::to_string(refined.vertexCount()) + " vertices)";
    }
    // The refinement's tables went to the pool (up to half the RAM): a viewer keeps none idle.
    clearTablePool();
    return done;
  });
  return {path, {}};
}

DocumentResult Document::pollExport() {
  if (!exportJob_.finished()) return {};
  DocumentResult result;
  try {
    result.notice = info(*exportJob_.poll());
    editError_.clear();
  } catch (const std::exception& e) {
    // Bad levels, a full disk, an unwritable folder: the atomic writers left nothing behind.
    result = editFailed(oneLine(std::string("could not write ") + exportTarget_ + ": " + e.what()));
  }
  exportTarget_.clear();
  return result;
}

std::filesystem::path Document::outputFolder() const {
  // Beside the model file, or in the current directory for the built-in model.
  const std::string& loaded = file_.loadedPath;
  const bool builtIn = loaded.empty() || loaded == defaultModelAsset();
  return builtIn ? std::filesystem::path() : std::filesystem::path(loaded).parent_path();
}

std::string Document::outputStem() const {
  // The file's own name (the built-in model opened by its path too: "default"), else a generated one's.
  const std::string& loaded = file_.loadedPath;
  if (!loaded.empty()) return std::filesystem::path(loaded).stem().string();
  return file_.modelName.rfind("default", 0) == 0 ? "default" : "model";
}

std::string Document::defaultSavePath() const { return (outputFolder() / (outputStem() + "_edited.obj")).string(); }

std::string Document::defaultSurfacePath(SchemeChoice scheme, int level, const std::string& formatName) const {
  const ExportFormat* format = exportFormatNamed(formatName);
  return (outputFolder() / (outputStem() + outputTag(scheme, level) + (format ? format->extensions.front() : ".bv"))).string();
}

void Document::reportEdit(const BuiltSurface* shown, const ViewerSettings& settings, EditStatus& edit) const {
  edit.selectedVertex = editor_.selected();
  if (edit.selectedVertex >= 0) edit.selectedPosition = editor_.points()[size_t(edit.selectedVertex)];
  edit.dragging = editor_.dragging();
  edit.undoSteps = int(editor_.undoCount());
  edit.redoSteps = int(editor_.redoCount());
  edit.undoLabel = editor_.undoLabel();
  edit.redoLabel = editor_.redoLabel();
  edit.movedVertices = movedVertices_;
  edit.exporting = exportJob_.running() ? exportTarget_ : std::string();
  edit.error = editError_;
  edit.positionsMs = lastEditCost_.positionsMs;
  edit.patchesMs = lastEditCost_.patchesMs;
  edit.uploadMs = lastEditCost_.uploadMs;
  edit.totalMs = lastEditCost_.totalMs;
  edit.updatedViews = lastEditCost_.views;
  // The exports write what the active view shows (its settings until it shows something).
  const View& active = settings.views[size_t(settings.clampedActiveView())];
  const SchemeChoice scheme = shown ? shown->key.scheme : active.scheme;
  const int level = shown ? shown->key.level : active.level;
  edit.defaultSavePath = defaultSavePath();
  edit.defaultSurfacePath = defaultSurfacePath(scheme, level, settings.edit.surfaceFormat);
  edit.defaultRefinedObjPath = (outputFolder() / (outputStem() + outputTag(scheme, level) + "_refined.obj")).string();
}

}  // namespace polarview
