// The model every view and command refines: a mesh with its analysis (model_analysis.h), made
// once per load by makeModel, and reading and checking a model file off the UI thread.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/poly_mesh.h"

namespace polarview {

class ModelAnalysis;

// The model every view refines: the mesh, where it came from and what its faces determine. An edit
// replaces `mesh` by a copy with new points (the faces stay) and bumps `points`, keeping the
// analysis; a load makes a new Model (makeModel) and bumps `generation`.
struct Model {
  std::shared_ptr<const PolyMesh> mesh;
  std::string name;        // file path or "default: ..."
  uint64_t generation = 0;
  uint64_t points = 0;     // revision of mesh->points within this generation
  bool radialForRtsBps = false;  // RTS/BPS refine the whole mesh radially (faces x2 a level, not x4)
  // Tables, poles and face estimates, made once for the faces and shared by copies and edits of
  // this model (a view of a Model without one throws std::invalid_argument).
  std::shared_ptr<const ModelAnalysis> analysis;
  // The OBJ text the mesh was read from, as read at load time (null for generated models and
  // conversions): Save OBJ writes the edited points into it (obj_io.h saveObjEdited).
  std::shared_ptr<const std::string> sourceText;
};

// The Model of a mesh (read and checked: checkModelMesh) with its analysis: the one way to make a
// Model views can refine. [O(corners log corners)]
Model makeModel(std::shared_ptr<const PolyMesh> mesh, std::string name, uint64_t generation);

// A model file read and checked off the UI thread: the mesh, or the error of the first problem.
struct LoadedModel {
  std::string path;
  // The mesh with its analysis and the file's bytes as read (Model::sourceText), made on the worker
  // thread: the window only adopts it (its generation is the adopter's to set).
  Model model;
  std::vector<std::string> warnings;  // non-fatal findings of the OBJ reader
  std::string error;                  // empty when the mesh is usable
};

// Reads an OBJ and checks it the way the viewer needs (manifold, supported, has faces); worker-
// thread safe. Never throws: failures come back in LoadedModel::error. [O(file)]
LoadedModel readModelFile(const std::string& path);
// The smallest extent (largest coordinate difference) of a model the viewer and `render` take.
constexpr double kSmallestModelExtent = 1e-150;
// Checks a mesh for the viewer (the topology the refiners need, at least one face, an extent of at
// least kSmallestModelExtent); returns the error message, empty when usable. [O(mesh)]
std::string checkModelMesh(const PolyMesh& mesh, const std::string& name);
// The same faces-and-extent check for the commands that compute curvature (continuity, export to
// ply and glb): throws InputError(name, 0, ...) for a mesh without faces or smaller than
// kSmallestModelExtent. [O(mesh)]
void requireCurvatureExtent(const PolyMesh& mesh, const std::string& name);
// The same for a model made with makeModel: its analysis has built the tables already. [O(points)]
std::string checkModel(const Model& model);
// The model's analysis: throws std::invalid_argument for a Model made without makeModel (an error
// in the caller). [O(1)]
const ModelAnalysis& analysisOf(const Model& model);

}  // namespace polarview
