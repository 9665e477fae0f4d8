#include "pipeline/model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/topology.h"
#include "pipeline/model_analysis.h"

namespace polarview {

namespace {
// The checks beyond the tables: faces, and an extent whose curvature double can hold.
std::string checkMeshShape(const PolyMesh& mesh, const std::string& name) {
  if (mesh.points.empty() || mesh.faceCount() == 0) return name + ": no faces";
  // Curvature goes as 1 / size^2: below 1e-150 it leaves double's range (1.8e308) and nothing can be
  // shaded; the reader's 1e150 bounds the other end.
  double extent = 0.0;
  for (const Point& p : mesh.points)
    for (int c = 0; c < 3; ++c) extent = std::max(extent, std::abs(p[c] - mesh.points[0][c]));
  if (extent < kSmallestModelExtent) {
    char text[160];
    std::snprintf(text, sizeof text, ": the model spans %.3g, below %.0e: its curvature (1 / size^2) is past double's range; scale it up",
                  extent, kSmallestModelExtent);
    return name + text;
  }
  return {};
}
}  // namespace

void requireCurvatureExtent(const PolyMesh& mesh, const std::string& name) {
  const std::string error = checkMeshShape(mesh, name);
  if (!error.empty()) throw InputError(name, 0, error.substr(name.size() + 2));
}

std::string checkModelMesh(const PolyMesh& mesh, const std::string& name) {
  try {
    ManifoldSplit split;  // non-manifold meshes are refined as their split (manifold_split.h)
    MeshTopology topology;
    refinableMesh(mesh, split, topology, name);  // throws InputError for meshes even that cannot refine
  } catch (const std::exception& e) {
    return e.what();
  }
  return checkMeshShape(mesh, name);
}

std::string checkModel(const Model& model) {
  if (!model.analysis->error().empty()) return model.analysis->error();  // refinableMesh's message
  return checkMeshShape(*model.mesh, model.name);
}

LoadedModel readModelFile(const std::string& path) {
  LoadedModel loaded;
  loaded.path = path;
  try {
    std::string text;
    PolyMesh mesh = loadObj(path, &loaded.warnings, &text);
    // The analysis (tables, poles, the refinability check) here, off the window's thread.
    loaded.model = makeModel(std::make_shared<const PolyMesh>(std::move(mesh)), path, 0);
    loaded.error = checkModel(loaded.model);
    if (loaded.error.empty()) loaded.model.sourceText = std::make_shared<const std::string>(std::move(text));
  } catch (const std::exception& e) {
    // InputError (FILE:LINE: ...), a missing file, bad_alloc on a huge one: the model stays.
    loaded.error = e.what();
  }
  return loaded;
}

Model makeModel(std::shared_ptr<const PolyMesh> mesh, std::string name, uint64_t generation) {
  Model model;
  if (mesh) {
    model.analysis = std::make_shared<const ModelAnalysis>(*mesh, name);
    model.radialForRtsBps = model.analysis->radialForRtsBps();
  }
  model.mesh = std::move(mesh);
  model.name = std::move(name);
  model.generation = generation;
  return model;
}

const ModelAnalysis& analysisOf(const Model& model) {
  if (!model.analysis) throw std::invalid_argument(model.name + ": a Model without its analysis (make it with makeModel)");
  return *model.analysis;
}

}  // namespace polarview
