// Live editing of the base control mesh (the control net the views draw): picking a control vertex
// on screen, moving it in the camera-facing plane through it, and undo / redo over whole drags.
// CPU math on GLM only: no GL, no ImGui (the app hands in cursor positions and view matrices, and
// turns changed points into positions-only surface updates, pipeline/surface_build.h refreshSurface).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/mesh/poly_mesh.h"
#include "pipeline/screen_rect.h"

namespace polarview {

// A view as drawn: world -> clip (projection * view, the matrices the renderer gets) and the
// view's rectangle in window coordinates (x right, y down).
struct ViewTransform {
  glm::dmat4 viewProjection{1.0};
  ScreenRect rect;

  // Window position (x, y) of `p` and its depth in normalised device coordinates (-1 near, 1 far);
  // nullopt behind the eye or outside the near and far planes. [O(1)]
  std::optional<glm::dvec3> project(const Point& p) const;
  // The point of the plane through `anchor` with normal `normal` under window position (x, y);
  // nullopt when the ray through it runs parallel to the plane. [O(1)]
  std::optional<Point> pointOnPlane(float x, float y, const Point& anchor, const glm::dvec3& normal) const;
};

// The vertex whose projection lies within `radius` pixels of (x, y), the one nearest the eye when
// several do; -1 when none. [O(points)]
int pickVertex(const std::vector<Point>& points, const ViewTransform& view, float x, float y,
               float radius = kPickRadiusPixels);

// One undoable change of the base points: the vertices it moved, from where to where.
struct PointEdit {
  struct Move {
    Index vertex = 0;
    Point before{0.0}, after{0.0};
  };
  std::vector<Move> moves;
  std::string what;  // "move vertex 12", "reset"
};

// The edited points of one model, the selected vertex, the drag in progress and the history.
class ControlMeshEditor {
 public:
  // Starts over on a newly loaded model: its points are what Reset returns to; no selection, no
  // history. [O(points)]
  void start(const std::vector<Point>& loadedPoints);
  const std::vector<Point>& points() const { return points_; }
  const std::vector<Point>& loadedPoints() const { return loaded_; }

  int selected() const { return selected_; }
  // -1 clears the selection; an index out of range too.
  void select(int vertex);
  bool dragging() const { return drag_.has_value(); }

  // A press on `vertex` at window position (x, y) in `view`: selects it and starts a drag in the
  // plane through it facing the camera (`viewDirection`, eye towards the scene). False (no drag)
  // for a vertex out of range or a degenerate view.
  bool beginDrag(int vertex, const ViewTransform& view, const glm::dvec3& viewDirection, float x, float y);
  // The cursor is at (x, y) in `view` (the drag's view, possibly zoomed since): the vertex moves by
  // the cursor's motion within the drag's plane, so it stays under the cursor as picked. True when
  // the point changed.
  bool dragTo(const ViewTransform& view, float x, float y);
  // The button was released: the whole drag becomes one undo step (none when nothing moved).
  void endDrag();

  // Undo / redo one step, or Reset: every vertex back to the loaded position (itself one step, so
  // it can be undone). False (nothing changes) when there is nothing to do.
  bool undo();
  bool redo();
  bool resetToLoaded();
  size_t undoCount() const { return undo_.size(); }
  size_t redoCount() const { return redo_.size(); }
  // What the next undo / redo would do ("" when nothing).
  std::string undoLabel() const { return undo_.empty() ? std::string() : undo_.back().what; }
  std::string redoLabel() const { return redo_.empty() ? std::string() : redo_.back().what; }
  // Vertices whose position differs from the loaded one. [O(points)]
  int movedVertexCount() const;

 private:
  void apply(const PointEdit& edit, bool forward);
  void push(PointEdit edit);

  struct Drag {
    int vertex = -1;
    Point start{0.0};        // the vertex where the drag began
    Point grab{0.0};         // the cursor's point on the plane at the press
    glm::dvec3 normal{0.0};  // the plane's normal: the camera's direction at the press
  };
  static constexpr size_t kMaxUndoSteps = 1000;
  std::vector<Point> loaded_, points_;
  std::vector<PointEdit> undo_, redo_;
  int selected_ = -1;
  std::optional<Drag> drag_;
};

}  // namespace polarview
