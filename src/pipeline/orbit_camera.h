// OrbitCamera: a turntable camera around a pivot (z is up), the one the viewer's views and the
// `render` command share. Plain data plus GLM math: no GL, no ImGui.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace polarview {

enum class ViewPreset { Front, Top, Side, Iso };

struct OrbitCamera {
  glm::dvec3 target{0.0};  // pivot the camera orbits and looks at
  double distance = 3.0;   // eye to target
  double yawDeg = -60.0;   // azimuth of the eye around +z, 0 = on +x
  // Default: a raised three-quarter view (40 deg up) so a pole on top of the model (the polar cap
  // the tool is about) faces the viewer instead of sitting on the silhouette.
  double pitchDeg = 40.0;  // elevation of the eye, clamped to (-89, 89) so +z stays up
  double fovDeg = 35.0;    // vertical field of view
  // Orthographic projection showing what the perspective one shows at the target's depth
  // (half height distance * tan(fov / 2)); zoom and pan work alike.
  bool orthographic = false;

  glm::dvec3 eye() const;
  glm::dvec3 forward() const;  // unit, eye -> target
  glm::dvec3 right() const;    // unit, screen x
  glm::dvec3 up() const;       // unit, screen y

  // View and projection matrices; the scene's bounding sphere sets near/far so it is never clipped
  // (near no further than distance / 100 from the eye, so close-ups keep what is in front).
  glm::dmat4 viewMatrix() const;
  glm::dmat4 projectionMatrix(double aspect, const glm::dvec3& sceneCentre, double sceneRadius) const;

  // Left drag: turns by pixel deltas (0.4 degrees per pixel).
  void orbit(double dxPixels, double dyPixels);
  // Right/middle drag: moves the target in the screen plane so the point under the cursor follows it.
  void pan(double dxPixels, double dyPixels, double viewportHeightPixels);
  // Wheel: each notch moves 15% closer (positive) or further (negative), down to a distance of
  // 1e-12 |target| (deep poles: the innermost ring of level L is ~2^-L of the model).
  void zoom(double wheelNotches);
  // Wheel over a view: zooms as zoom() and moves the target so that the point of the target's
  // plane under the cursor (ndcX, ndcY in [-1, 1], y up) stays under it. `aspect` = width / height.
  void zoomAt(double wheelNotches, double ndcX, double ndcY, double aspect);
  // Wheel over the surface: scales the camera's placement about `point` (the surface point under
  // the cursor) by the zoom factor, keeping the direction: the point stays where it is on screen and
  // the eye approaches it without ever passing it (zooming in never flies through the surface).
  void zoomTowards(const glm::dvec3& point, double wheelNotches);
  // Double-click: the pivot becomes `point`; the eye stays where it is and turns to look at it.
  void setPivotKeepingEye(const glm::dvec3& point);
  // F: centres the bounding box and, keeping the direction, backs off until its eight corners fit
  // a view of `aspect` (width / height) both ways with an 8% margin.
  void frame(const glm::dvec3& boxMin, const glm::dvec3& boxMax, double aspect = 1.0);
  // The same for `count` points (a model's control points, whose hull holds its limit surface):
  // target at the centre of their box, distance so that every point fits within the middle
  // `heightFraction` of the view's height (room for the view's title above). [O(count)]
  void framePoints(const glm::dvec3* points, size_t count, double aspect = 1.0, double heightFraction = 1.0);
  // Presets keep target and distance and set the direction.
  void applyPreset(ViewPreset preset);
};

const char* viewPresetName(ViewPreset preset);

// {"target":[x,y,z],"distance":d,"yaw":deg,"pitch":deg,"fov":deg,"ortho":false} with 17 significant
// digits.
std::string cameraToJson(const OrbitCamera& camera);

// Parses a JSON object with any subset of the keys above over `base` (missing keys keep base's
// values). Returns nullopt and sets `error` on malformed text, unknown keys or non-finite values.
std::optional<OrbitCamera> cameraFromJson(const std::string& json, const OrbitCamera& base, std::string* error);

}  // namespace polarview
