#include "web_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include "core/export/tessellation.h"
#include "pipeline/level_limits.h"
#include "pipeline/pole_inspection.h"

namespace polarview {

// [SECTION] Model

std::string WebScene::loadObj(const std::string& path, const std::string& name) {
  LoadedModel loaded = readModelFile(path);
  if (!loaded.error.empty()) {
    // The reader names the file by its path in the page's memory: the user knows it by its name.
    std::string error = loaded.error;
    if (error.compare(0, path.size(), path) == 0) error = name + error.substr(path.size());
    else error = name + ": " + error;
    return error;
  }
  model_ = loaded.model;
  model_.name = name;
  model_.generation = ++generation_;
  // The box of the control points holds the limit surface: its centre keeps float precision.
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const Point& p : model_.mesh->points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  centre_ = 0.5 * (lo + hi);
  radius_ = std::max(0.5 * glm::length(hi - lo), 1e-300);
  unit_ = std::ldexp(1.0, std::ilogb(radius_));
  views_.clear();
  poles_.clear();
  ++revision_;
  return {};
}

int WebScene::deepestLevel(SchemeChoice scheme) const {
  return hasModel() ? polarview::deepestLevel(model_, scheme, kWebFaceBudget) : 0;
}

// [SECTION] Views

ViewMesh WebScene::buildView(SchemeChoice scheme, int level) const {
  ViewMesh view;
  view.scheme = scheme;
  view.level = level;
  const auto start = std::chrono::steady_clock::now();
  try {
    // The desktop's build (refine, patches, curvature samples), then the exporter's welded mesh.
    SurfaceKey key;
    key.model = model_.generation;
    key.scheme = scheme;
    key.level = level;
    view.surface = buildSurface(model_, key, kWebFaceBudget);
    PatchSet set;
    set.patches = view.surface->patches;
    for (const Patch& patch : set.patches) ++set.kindCounts[size_t(patch.kind)];
    const double perPatch = double(kWebTriangleBudget) / (2.0 * std::max<size_t>(set.patches.size(), 1));
    view.samples = std::clamp(int(std::floor(std::sqrt(perPatch))), 1, kWebMaxSamples);
    const Tessellation mesh = tessellatePatchSet(set, view.samples);

    // Interleave: position relative to the centre in units of unit(), normal, K and H in those
    // units (float: the GPU's precision and range; the camera and the colour range are scaled
    // alike when drawn).
    const double unitK = unit_ * unit_, unitH = unit_;
    view.vertices.resize(mesh.positions.size() * kWebVertexFloats);
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      float* out = &view.vertices[v * kWebVertexFloats];
      const glm::dvec3 p = (mesh.positions[v] - centre_) / unit_;
      const auto finite = [](double x) { return std::isfinite(x) ? float(std::clamp(x, -3e38, 3e38)) : 0.0f; };
      out[0] = float(p.x), out[1] = float(p.y), out[2] = float(p.z);
      out[3] = float(mesh.normals[v].x), out[4] = float(mesh.normals[v].y), out[5] = float(mesh.normals[v].z);
      out[6] = finite(mesh.gaussian[v] * unitK);
      out[7] = finite(mesh.mean[v] * unitH);
    }
    view.indices.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) view.indices.insert(view.indices.end(), t.begin(), t.end());
  } catch (const std::exception& e) {
    view.surface.reset();
    view.error = e.what();
  }
  view.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return view;
}

void WebScene::setViews(const std::vector<SchemeChoice>& schemes, int level) {
  if (!hasModel()) return;
  std::vector<ViewMesh> next;
  for (SchemeChoice scheme : schemes) {
    // A view of the same scheme and level is kept (another view's scheme changed).
    auto same = std::find_if(views_.begin(), views_.end(),
                             [&](const ViewMesh& v) { return v.scheme == scheme && v.level == level; });
    if (same != views_.end()) next.push_back(*same);
    else next.push_back(buildView(scheme, level));
  }
  bool changed = next.size() != views_.size();
  for (size_t v = 0; !changed && v < next.size(); ++v)
    changed = next[v].scheme != views_[v].scheme || next[v].level != views_[v].level;
  views_ = std::move(next);
  if (changed) ++revision_;
}

// [SECTION] Colour range, picks, poles

ColourInterval WebScene::colourRange(ShadingParams::Mode mode, std::vector<float>* histogram) const {
  if (rangesRevision_ != revision_) ranges_.clear(), rangesRevision_ = revision_;
  if (auto known = ranges_.find(int(mode)); known != ranges_.end()) {
    if (histogram) *histogram = known->second.second;
    return known->second.first;
  }
  std::vector<double> values, weights;
  for (const ViewMesh& view : views_) {
    if (!view.surface || !view.surface->samples) continue;
    const CurvatureSamples& s = *view.surface->samples;
    const std::vector<double>& samples = mode == ShadingParams::Mode::Mean ? s.mean : s.gaussian;
    double area = 0.0;
    for (double a : s.areas) area += a;
    if (!(area > 0.0)) continue;
    values.insert(values.end(), samples.begin(), samples.end());
    for (double a : s.areas) weights.push_back(a / area);
  }
  if (values.empty()) return {};
  // The desktop's default: automatic, symmetric, P90 (session/settings_rules.cpp automaticInterval).
  const ColourInterval range = colourStatistics(values, weights, 0.90f).automaticInterval();
  std::vector<float>& bins = ranges_[int(mode)].second;
  bins = weightedHistogram(values, weights, range, 48);
  ranges_[int(mode)].first = range;
  if (histogram) *histogram = bins;
  return range;
}

std::optional<PointReadout> WebScene::pick(int view, const glm::dvec3& origin, const glm::dvec3& direction) const {
  if (view < 0 || size_t(view) >= views_.size() || !views_[size_t(view)].surface) return std::nullopt;
  const ViewMesh& mesh = views_[size_t(view)];
  // Moeller-Trumbore over every triangle: the nearest hit in front of the eye.
  double nearest = std::numeric_limits<double>::infinity();
  auto vertex = [&](uint32_t i) {
    const float* p = &mesh.vertices[size_t(i) * kWebVertexFloats];
    return unit_ * glm::dvec3(p[0], p[1], p[2]);
  };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = vertex(mesh.indices[t]), b = vertex(mesh.indices[t + 1]), c = vertex(mesh.indices[t + 2]);
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300) continue;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(direction, q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double hit = glm::dot(e2, q) / det;
    if (hit > 0.0 && hit < nearest) nearest = hit;
  }
  if (!std::isfinite(nearest)) return std::nullopt;
  // The facet's point lies within a chord's height of the surface: a few percent of the radius.
  const Point picked = centre_ + origin + nearest * direction;
  return readSurfacePoint(mesh.surface->patches, picked, 0.05 * radius_);
}

std::vector<PoleLine> WebScene::poles(SchemeChoice scheme, size_t listed) const {
  if (auto known = poles_.find(int(scheme)); known != poles_.end()) return known->second;
  std::vector<PoleLine>& lines = poles_[int(scheme)];
  if (!hasModel()) return lines;
  for (Index vertex : modelPoles(*model_.mesh)) {
    if (lines.size() >= listed) break;
    PoleLine line;
    line.vertex = int(vertex);
    try {
      const PoleInspection inspection = inspectPole(*model_.mesh, vertex, scheme, 0);
      line.valence = inspection.valence;
      line.curvatureDefined = inspection.curvatureDefined;
      line.K = inspection.K;
      line.H = inspection.H;
      line.note = inspection.note;
    } catch (const std::exception& e) {
      line.note = e.what();
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace polarview
