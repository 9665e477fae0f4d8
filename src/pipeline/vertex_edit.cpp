// Control-vertex picking, dragging and the edit history (see vertex_edit.h).
#include "pipeline/vertex_edit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace polarview {

// [SECTION] Projection

std::optional<glm::dvec3> ViewTransform::project(const Point& p) const {
  const glm::dvec4 clip = viewProjection * glm::dvec4(p, 1.0);
  if (!(clip.w > 0.0)) return std::nullopt;  // behind the eye (perspective) or degenerate
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  if (!(std::abs(ndc.z) <= 1.0)) return std::nullopt;
  // NDC -> window: the mapping drawViews gives glViewport, with y flipped to ImGui's y down.
  return glm::dvec3(double(rect.x) + 0.5 * (ndc.x + 1.0) * double(rect.w),
                    double(rect.y) + 0.5 * (1.0 - ndc.y) * double(rect.h), ndc.z);
}

std::optional<Point> ViewTransform::pointOnPlane(float x, float y, const Point& anchor, const glm::dvec3& normal) const {
  // The ray through the window position: its points on the near and far planes, unprojected.
  const double ndcX = 2.0 * (double(x) - rect.x) / std::max(double(rect.w), 1.0) - 1.0;
  const double ndcY = 1.0 - 2.0 * (double(y) - rect.y) / std::max(double(rect.h), 1.0);
  const glm::dmat4 inverse = glm::inverse(viewProjection);
  const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
  const glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
  if (nearPoint.w == 0.0 || farPoint.w == 0.0) return std::nullopt;
  const glm::dvec3 a = glm::dvec3(nearPoint) / nearPoint.w, b = glm::dvec3(farPoint) / farPoint.w;
  // Where it meets the plane through the anchor.
  const double along = glm::dot(b - a, normal);
  if (!(std::abs(along) > 1e-300) || !std::isfinite(along)) return std::nullopt;
  const Point hit = a + (b - a) * (glm::dot(anchor - a, normal) / along);
  if (!std::isfinite(hit.x) || !std::isfinite(hit.y) || !std::isfinite(hit.z)) return std::nullopt;
  return hit;
}

int pickVertex(const std::vector<Point>& points, const ViewTransform& view, float x, float y, float radius) {
  int best = -1;
  double bestDepth = std::numeric_limits<double>::infinity();
  const double r2 = double(radius) * double(radius);
  for (size_t i = 0; i < points.size(); ++i) {
    const std::optional<glm::dvec3> w = view.project(points[i]);
    if (!w) continue;
    const double dx = w->x - x, dy = w->y - y;
    if (dx * dx + dy * dy > r2 || w->z >= bestDepth) continue;
    best = int(i);
    bestDepth = w->z;
  }
  return best;
}

// [SECTION] Editor

void ControlMeshEditor::start(const std::vector<Point>& loadedPoints) {
  loaded_ = loadedPoints;
  points_ = loadedPoints;
  undo_.clear();
  redo_.clear();
  selected_ = -1;
  drag_.reset();
}

void ControlMeshEditor::select(int vertex) { selected_ = vertex >= 0 && size_t(vertex) < points_.size() ? vertex : -1; }

bool ControlMeshEditor::beginDrag(int vertex, const ViewTransform& view, const glm::dvec3& viewDirection, float x, float y) {
  endDrag();  // a press without the previous release (focus lost): keep what that drag did
  select(vertex);
  if (selected_ < 0 || !(glm::length(viewDirection) > 0.0)) return false;
  Drag drag;
  drag.vertex = selected_;
  drag.start = points_[size_t(selected_)];
  drag.normal = glm::normalize(viewDirection);
  std::optional<Point> grab = view.pointOnPlane(x, y, drag.start, drag.normal);
  if (!grab) return false;
  drag.grab = *grab;
  drag_ = drag;
  return true;
}

bool ControlMeshEditor::dragTo(const ViewTransform& view, float x, float y) {
  if (!drag_ || size_t(drag_->vertex) >= points_.size()) return false;
  const std::optional<Point> hit = view.pointOnPlane(x, y, drag_->start, drag_->normal);
  if (!hit) return false;
  const Point moved = drag_->start + (*hit - drag_->grab);
  Point& current = points_[size_t(drag_->vertex)];
  if (moved == current) return false;
  current = moved;
  return true;
}

void ControlMeshEditor::endDrag() {
  if (!drag_) return;
  const Drag drag = *drag_;
  drag_.reset();
  if (size_t(drag.vertex) >= points_.size() || points_[size_t(drag.vertex)] == drag.start) return;
  PointEdit edit;
  edit.moves.push_back({Index(drag.vertex), drag.start, points_[size_t(drag.vertex)]});
  edit.what = "move vertex " + std::to_string(drag.vertex);
  push(std::move(edit));
}

void ControlMeshEditor::push(PointEdit edit) {
  undo_.push_back(std::move(edit));
  if (undo_.size() > kMaxUndoSteps) undo_.erase(undo_.begin());
  redo_.clear();
}

void ControlMeshEditor::apply(const PointEdit& edit, bool forward) {
  for (const PointEdit::Move& move : edit.moves) points_[size_t(move.vertex)] = forward ? move.after : move.before;
}

bool ControlMeshEditor::undo() {
  endDrag();
  if (undo_.empty()) return false;
  apply(undo_.back(), false);
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  return true;
}

bool ControlMeshEditor::redo() {
  endDrag();
  if (redo_.empty()) return false;
  apply(redo_.back(), true);
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  return true;
}

bool ControlMeshEditor::resetToLoaded() {
  endDrag();
  PointEdit edit;
  edit.what = "reset";
  for (size_t i = 0; i < points_.size(); ++i)
    if (points_[i] != loaded_[i]) edit.moves.push_back({Index(i), points_[i], loaded_[i]});
  if (edit.moves.empty()) return false;
  apply(edit, true);
  push(std::move(edit));
  return true;
}

int ControlMeshEditor::movedVertexCount() const {
  int moved = 0;
  for (size_t i = 0; i < points_.size(); ++i) moved += points_[i] != loaded_[i];
  return moved;
}

}  // namespace polarview
