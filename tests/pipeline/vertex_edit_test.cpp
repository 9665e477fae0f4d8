// Control-vertex picking and the edit history (pipeline/vertex_edit.h), without a window.
#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/orbit_camera.h"
#include "pipeline/vertex_edit.h"

namespace polarview {
TEST_CASE("vertex picking: within the radius the vertex nearest the eye wins, outside it none") {
  OrbitCamera camera;
  camera.target = glm::dvec3(0.0);
  camera.distance = 5.0;
  ViewTransform view;
  view.rect = ScreenRect{100, 50, 400, 300};
  view.viewProjection = glm::dmat4(camera.projectionMatrix(400.0 / 300.0, glm::dvec3(0.0), 2.0)) *
                        glm::lookAt(camera.eye(), camera.target, camera.up());
  // Three points on one line of sight (same pixel) at different depths, and one off to the side.
  const glm::dvec3 toEye = glm::normalize(camera.eye() - camera.target);
  std::vector<Point> points = {Point(0.0) - 0.5 * toEye, Point(0.0) + 0.5 * toEye, Point(0.0),
                               Point(0.0) + 1.5 * camera.right()};
  const auto centre = view.project(points[2]);
  REQUIRE(centre);
  CHECK(centre->x == doctest::Approx(300.0).epsilon(1e-9));
  CHECK(centre->y == doctest::Approx(200.0).epsilon(1e-9));
  CHECK(pickVertex(points, view, 303.0f, 196.0f) == 1);  // 5 px off: the one nearest the eye
  CHECK(pickVertex(points, view, 300.0f, 209.0f) == -1);  // 9 px off: none
  const auto side = view.project(points[3]);
  REQUIRE(side);
  CHECK(pickVertex(points, view, float(side->x) - 7.0f, float(side->y)) == 3);
  // A point on the drag plane through a vertex projects back under the cursor.
  const auto onPlane = view.pointOnPlane(321.5f, 187.25f, points[3], camera.forward());
  REQUIRE(onPlane);
  const auto back = view.project(*onPlane);
  CHECK(back->x == doctest::Approx(321.5).epsilon(1e-9));
  CHECK(back->y == doctest::Approx(187.25).epsilon(1e-9));
  CHECK(std::abs(glm::dot(*onPlane - points[3], camera.forward())) < 1e-12);
}


}  // namespace polarview
