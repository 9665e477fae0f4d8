// What the page shows, without WebGL: the model, one triangle mesh per view made by the core's
// exporter (tessellation.h: watertight, exact normal, K and H per vertex; WebGL2 has no
// tessellation shaders), the shared colour range, picks and the poles' K and H. web_gl.cpp draws
// it; web_main.cpp owns it.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/model.h"
#include "pipeline/point_readout.h"
#include "pipeline/shading.h"
#include "pipeline/surface_build.h"

namespace polarview {

// Floats per vertex of ViewMesh::vertices: position (relative to the model centre), unit normal,
// K and H, all in units of WebScene::unit() (position / unit, K * unit^2, H * unit: the desktop's
// GPU units).
constexpr int kWebVertexFloats = 8;
// Triangles one view's mesh may have; the samples per patch edge follow (1..kWebMaxSamples).
constexpr size_t kWebTriangleBudget = 400000;
constexpr int kWebMaxSamples = 12;
// Faces one view may refine: a tenth of the desktop's (a page's wasm32 memory is 2 GB at most).
constexpr size_t kWebFaceBudget = 400000;

// One view's drawable surface.
struct ViewMesh {
  SchemeChoice scheme = SchemeChoice::C2PS;
  int level = 0;
  std::shared_ptr<const BuiltSurface> surface;  // patches (picks), poles (markers), curvature samples
  std::vector<float> vertices;                  // kWebVertexFloats per vertex
  std::vector<uint32_t> indices;                // three per triangle
  int samples = 0;                              // segments per patch edge
  std::string error;                            // why there is no surface (the level over the budget, ...)
  double buildMs = 0.0;
};

// One pole's numbers for the panel (pole_inspection.h's inspectPole).
struct PoleLine {
  int vertex = -1, valence = 0;
  bool curvatureDefined = false;
  double K = 0.0, H = 0.0;
  std::string note;
};

class WebScene {
 public:
  // Reads and checks an OBJ (readModelFile) and makes it the model; on failure keeps the previous
  // model and returns the error (the page shows it). `name` is what the page calls the file.
  std::string loadObj(const std::string& path, const std::string& name);
  const Model& model() const { return model_; }
  bool hasModel() const { return model_.mesh != nullptr; }
  // Centre and radius of the control points' bounding box (the views' positions are relative to it).
  const glm::dvec3& centre() const { return centre_; }
  double radius() const { return radius_; }
  // The power of two nearest below the radius (the desktop's PatchRenderer unit_): the vertices
  // carry position / unit, K * unit^2 and H * unit, so a model of any size keeps float's precision
  // and range (K of a model 1e20 across is below float's smallest normal, of one 1e-20 across above
  // its largest; the shader's dot(P, P) of either over- or underflows).
  double unit() const { return unit_; }

  // The views' meshes for `schemes` at `level`: rebuilt for what changed, kept otherwise. [O(output)]
  void setViews(const std::vector<SchemeChoice>& schemes, int level);
  const std::vector<ViewMesh>& views() const { return views_; }
  // Bumped whenever a view's mesh changes (the GPU copy follows it).
  uint64_t revision() const { return revision_; }

  // One colour range over every view's curvature samples (each view weighted by its own area, as
  // the desktop's Session::collectColourSamples), the automatic range of the desktop's default
  // settings (symmetric, P90), and the histogram over it. [O(samples log samples)]
  ColourInterval colourRange(ShadingParams::Mode mode, std::vector<float>* histogram) const;

  // The surface point of view `view` where the ray origin + t direction (relative to the model
  // centre) first meets its mesh, refined on the patches (readSurfacePoint). [O(triangles)]
  std::optional<PointReadout> pick(int view, const glm::dvec3& origin, const glm::dvec3& direction) const;

  // K and H at the model's poles under `scheme` (the first `listed` poles). [O(poles)]
  std::vector<PoleLine> poles(SchemeChoice scheme, size_t listed) const;

  // The deepest level `scheme` may go on this model within kWebFaceBudget.
  int deepestLevel(SchemeChoice scheme) const;

 private:
  ViewMesh buildView(SchemeChoice scheme, int level) const;

  Model model_;
  uint64_t generation_ = 0;
  glm::dvec3 centre_{0.0};
  double radius_ = 1.0;
  double unit_ = 1.0;
  std::vector<ViewMesh> views_;
  uint64_t revision_ = 0;
  // What colourRange and poles computed, for the scene's revision (they run every frame).
  mutable std::map<int, std::pair<ColourInterval, std::vector<float>>> ranges_;
  mutable uint64_t rangesRevision_ = ~uint64_t(0);
  mutable std::map<int, std::vector<PoleLine>> poles_;
};

}  // namespace polarview
