#include "pipeline/orbit_camera.h"

#include "core/mesh/constants.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace polarview {
namespace {

constexpr double kMaxPitchDeg = 89.0;  // keeps +z up without a roll flip at the poles of the orbit
constexpr double kOrbitDegPerPixel = 0.4;
constexpr double kZoomPerNotch = 0.85;
// Closest zoom, relative to the target's distance from the origin: far below the innermost ring of
// a level-24 radial refinement (~6e-8 of the model), and still 1e4 times the double rounding of the
// eye position. No absolute floor or ceiling beyond the double range: models from 1e-150 to 1e150
// (README, OBJ) are framed and zoomed alike.
constexpr double kMinDistanceRelative = 1e-12;
constexpr double kMinDistance = 1e-290, kMaxDistance = 1e290;
constexpr double kNearPerDistance = 1e-2;  // perspective near plane floor, times the distance

double radians(double deg) { return deg * kPi / 180.0; }
double degrees(double rad) { return rad * 180.0 / kPi; }

// Minimal JSON reader for one flat object of numbers and number arrays (all a camera needs).
class JsonCursor {
 public:
  explicit JsonCursor(const std::string& text) : s_(text) {}
  void skipSpace() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool consume(char c) {
    skipSpace();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  bool atEnd() {
    skipSpace();
    return i_ >= s_.size();
  }
  bool readString(std::string* out) {
    if (!consume('"')) return false;
    size_t end = s_.find('"', i_);
    if (end == std::string::npos) return false;
    *out = s_.substr(i_, end - i_);
    i_ = end + 1;
    return true;
  }
  bool readNumber(double* out) {
    skipSpace();
    // JSON's booleans read as 1 and 0 (the "ortho" key).
    for (const auto& [word, value] : {std::pair{"true", 1.0}, std::pair{"false", 0.0}}) {
      const size_t length = std::char_traits<char>::length(word);
      if (s_.compare(i_, length, word) == 0) {
        i_ += length;
        *out = value;
        return true;
      }
    }
    const char* begin = s_.c_str() + i_;
    char* end = nullptr;
    *out = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(*out)) return false;
    i_ += size_t(end - begin);
    return true;
  }
  // Reads a number or an array of numbers.
  bool readValue(std::vector<double>* out) {
    out->clear();
    double x = 0.0;
    if (!consume('[')) {
      if (!readNumber(&x)) return false;
      out->push_back(x);
      return true;
    }
    if (consume(']')) return true;
    do {
      if (!readNumber(&x)) return false;
      out->push_back(x);
    } while (consume(','));
    return consume(']');
  }

 private:
  const std::string& s_;
  size_t i_ = 0;
};

}  // namespace

glm::dvec3 OrbitCamera::forward() const {
  double yaw = radians(yawDeg), pitch = radians(pitchDeg);
  return -glm::dvec3(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
}
glm::dvec3 OrbitCamera::eye() const { return target - distance * forward(); }
glm::dvec3 OrbitCamera::right() const {
  double yaw = radians(yawDeg);
  return glm::dvec3(-std::sin(yaw), std::cos(yaw), 0.0);
}
glm::dvec3 OrbitCamera::up() const { return glm::cross(right(), forward()); }

glm::dmat4 OrbitCamera::viewMatrix() const { return glm::lookAt(eye(), target, up()); }

glm::dmat4 OrbitCamera::projectionMatrix(double aspect, const glm::dvec3& sceneCentre, double sceneRadius) const {
  // Near/far bracket the scene's bounding sphere (with margin), with a floor on near so the depth
  // buffer keeps its precision when the eye is inside the sphere. Floors relative to the scene and
  // the distance: a model of 1e-10 is not a point of a 1e-6 sphere.
  const double size = std::max(sceneRadius, distance);
  double radius = std::max(sceneRadius, 1e-6 * size);
  double centreDepth = glm::dot(sceneCentre - eye(), forward());
  double farPlane = std::max(centreDepth + 1.5 * radius, 1e-6 * size);
  if (orthographic) {
    // The same picture at the target's depth as the perspective view (half height D tan(fov/2));
    // no eye to protect, so near may lie behind it.
    const double halfHeight = distance * std::tan(radians(fovDeg) / 2.0);
    const double halfWidth = halfHeight * std::max(aspect, 1e-6);
    return glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, centreDepth - 1.5 * radius, farPlane);
  }
  // The floor is also at most a hundredth of the distance to the target, so close-ups of a deep
  // pole (the eye 1e-6 of the model away or less) are not clipped; the surface is drawn relative to
  // the eye (patch_renderer.cpp), so its depth keeps float precision that near.
  double nearPlane = std::max(centreDepth - 1.5 * radius, std::min(farPlane * 1e-4, distance * kNearPerDistance));
  return glm::perspective(radians(fovDeg), std::max(aspect, 1e-6), nearPlane, farPlane);
}

void OrbitCamera::orbit(double dxPixels, double dyPixels) {
  yawDeg = std::remainder(yawDeg - kOrbitDegPerPixel * dxPixels, 360.0);
  pitchDeg = std::clamp(pitchDeg + kOrbitDegPerPixel * dyPixels, -kMaxPitchDeg, kMaxPitchDeg);
}

void OrbitCamera::pan(double dxPixels, double dyPixels, double viewportHeightPixels) {
  // World length of one pixel at the target's depth.
  double worldPerPixel = 2.0 * distance * std::tan(radians(fovDeg) / 2.0) / std::max(viewportHeightPixels, 1.0);
  target += worldPerPixel * (-dxPixels * right() + dyPixels * up());
}

void OrbitCamera::zoom(double wheelNotches) {
  const double closest = std::max(kMinDistanceRelative * glm::length(target), kMinDistance);
  distance = std::clamp(distance * std::pow(kZoomPerNotch, wheelNotches), closest, kMaxDistance);
}

void OrbitCamera::zoomTowards(const glm::dvec3& point, double wheelNotches) {
  const double before = distance;
  zoom(wheelNotches);
  target = point + (target - point) * (distance / before);
}

void OrbitCamera::zoomAt(double wheelNotches, double ndcX, double ndcY, double aspect) {
  // The point of the target's plane under the cursor, before the zoom.
  const double tanY = std::tan(radians(fovDeg) / 2.0), tanX = std::max(aspect, 1e-6) * tanY;
  const glm::dvec3 underCursor = target + distance * (ndcX * tanX * right() + ndcY * tanY * up());
  const double before = distance;
  zoom(wheelNotches);
  // Scaling the view about that point keeps it under the cursor (exactly on the target's plane).
  target = underCursor + (target - underCursor) * (distance / before);
}

void OrbitCamera::setPivotKeepingEye(const glm::dvec3& point) {
  glm::dvec3 eyeNow = eye();
  glm::dvec3 offset = eyeNow - point;
  double length = glm::length(offset);
  if (!(length > kMinDistanceRelative * glm::length(point)) || !(length > kMinDistance)) return;
  target = point;
  distance = length;
  yawDeg = degrees(std::atan2(offset.y, offset.x));
  pitchDeg = std::clamp(degrees(std::asin(std::clamp(offset.z / length, -1.0, 1.0))), -kMaxPitchDeg, kMaxPitchDeg);
}

void OrbitCamera::frame(const glm::dvec3& boxMin, const glm::dvec3& boxMax, double aspect) {
  std::vector<glm::dvec3> corners;
  corners.reserve(8);
  for (int corner = 0; corner < 8; ++corner) {
    corners.emplace_back((corner & 1) ? boxMax.x : boxMin.x, (corner & 2) ? boxMax.y : boxMin.y,
                         (corner & 4) ? boxMax.z : boxMin.z);
  }
  framePoints(corners.data(), corners.size(), aspect);
}

void OrbitCamera::framePoints(const glm::dvec3* points, size_t count, double aspect, double heightFraction) {
  if (count == 0) return;
  // Fits the points in the current viewing direction rather than a bounding sphere: the sphere of
  // a flat cap or of a wide mushroom seen from above filled only a third of the view.
  glm::dvec3 lo = points[0], hi = points[0];
  for (size_t i = 1; i < count; ++i) {
    lo = glm::min(lo, points[i]);
    hi = glm::max(hi, points[i]);
  }
  target = 0.5 * (lo + hi);
  constexpr double kMargin = 1.08;  // the outermost point lands at 1 / 1.08 of the half-width
  const double fullTanY = std::tan(radians(fovDeg) / 2.0) / kMargin;
  const double tanX = std::max(aspect, 1e-3) * fullTanY;
  const double tanY = fullTanY * std::clamp(heightFraction, 0.1, 1.0);
  // Orthographic: the view's half-size at any depth is D tan, so depth does not help.
  const double depthWeight = orthographic ? 0.0 : 1.0;
  const glm::dvec3 r = right(), u = up(), f = forward();
  double radius = std::max(0.5 * glm::length(hi - lo), 1e-6 * glm::length(target));
  if (!(radius > 0.0)) radius = 1e-6;  // one point at the origin: no size to go by
  double needed = 0.0;
  for (size_t i = 0; i < count; ++i) {
    // A point at depth z behind the target and offset x, y is inside when |x| <= tanX (D + z);
    // the eye stays in front of every point.
    glm::dvec3 d = points[i] - target;
    double depth = glm::dot(d, f);
    needed = std::max({needed, std::abs(glm::dot(d, r)) / tanX - depthWeight * depth,
                       std::abs(glm::dot(d, u)) / tanY - depthWeight * depth, 0.05 * radius - depth});
  }
  distance = needed;
}

void OrbitCamera::applyPreset(ViewPreset preset) {
  switch (preset) {
    case ViewPreset::Front: yawDeg = -90.0; pitchDeg = 0.0; break;
    case ViewPreset::Top: yawDeg = -90.0; pitchDeg = kMaxPitchDeg; break;
    case ViewPreset::Side: yawDeg = 0.0; pitchDeg = 0.0; break;
    case ViewPreset::Iso: yawDeg = -45.0; pitchDeg = degrees(std::atan(1.0 / std::sqrt(2.0))); break;
  }
}

const char* viewPresetName(ViewPreset preset) {
  switch (preset) {
    case ViewPreset::Front: return "front";
    case ViewPreset::Top: return "top";
    case ViewPreset::Side: return "side";
    case ViewPreset::Iso: return "iso";
  }
  return "?";
}

std::string cameraToJson(const OrbitCamera& c) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "{\"target\":[%.17g,%.17g,%.17g],\"distance\":%.17g,\"yaw\":%.17g,\"pitch\":%.17g,\"fov\":%.17g,"
                "\"ortho\":%s}",
                c.target.x, c.target.y, c.target.z, c.distance, c.yawDeg, c.pitchDeg, c.fovDeg,
                c.orthographic ? "true" : "false");
  return buffer;
}

std::optional<OrbitCamera> cameraFromJson(const std::string& json, const OrbitCamera& base, std::string* error) {
  auto fail = [&](const std::string& why) -> std::optional<OrbitCamera> {
    if (error) *error = "camera JSON: " + why;
    return std::nullopt;
  };
  OrbitCamera camera = base;
  JsonCursor cursor(json);
  if (!cursor.consume('{')) return fail("expected '{'");
  if (!cursor.consume('}')) {
    do {
      std::string key;
      std::vector<double> value;
      if (!cursor.readString(&key)) return fail("expected a quoted key");
      if (!cursor.consume(':')) return fail("expected ':' after \"" + key + "\"");
      if (!cursor.readValue(&value)) return fail("expected a finite number or [numbers] for \"" + key + "\"");
      bool scalar = value.size() == 1;
      if (key == "target" && value.size() == 3) camera.target = {value[0], value[1], value[2]};
      else if (key == "distance" && scalar && value[0] > 0.0) camera.distance = value[0];
      else if (key == "yaw" && scalar) camera.yawDeg = value[0];
      else if (key == "pitch" && scalar) camera.pitchDeg = std::clamp(value[0], -kMaxPitchDeg, kMaxPitchDeg);
      else if (key == "fov" && scalar && value[0] > 0.0 && value[0] < 180.0) camera.fovDeg = value[0];
      else if (key == "ortho" && scalar && (value[0] == 0.0 || value[0] == 1.0)) camera.orthographic = value[0] == 1.0;
      else return fail("bad key or value \"" + key +
                       "\" (keys: target[3], distance>0, yaw, pitch, fov in (0,180), ortho true/false)");
    } while (cursor.consume(','));
    if (!cursor.consume('}')) return fail("expected ',' or '}'");
  }
  if (!cursor.atEnd()) return fail("text after the closing '}'");
  return camera;
}

}  // namespace polarview
