#include "core/mesh/figure_shapes.h"

#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/mesh/shapes.h"

namespace polarview::shapes {

PolyMesh valence20Bump() {
  return heightCap(20, 8, [](double x, double y) { return 0.5 * std::exp(-(x * x / 0.5 + y * y / 0.25)); });
}

namespace {

// The surface of a box of nx x ny x nz cells whose lattice vertices are made on first use, so that
// the centres of the blocks left open for fingers do not exist.
class BoxSurface {
 public:
  BoxSurface(PolyMesh& mesh, glm::ivec3 cells, glm::dvec3 cellSize) : mesh_(mesh), cells_(cells), size_(cellSize) {
    ids_.assign(size_t((cells.x + 1) * (cells.y + 1) * (cells.z + 1)), -1);
  }
  Index vertex(glm::ivec3 p) {
    Index& id = ids_[size_t((p.z * (cells_.y + 1) + p.y) * (cells_.x + 1) + p.x)];
    if (id < 0) {
      id = mesh_.vertexCount();
      mesh_.points.push_back(glm::dvec3(p) * size_);
    }
    return id;
  }
  glm::dvec3 position(glm::ivec3 p) const { return glm::dvec3(p) * size_; }

 private:
  PolyMesh& mesh_;
  glm::ivec3 cells_;
  glm::dvec3 size_;
  std::vector<Index> ids_;
};

// One side of the box: lattice point origin + u * du + v * dv, with du x dv the outward normal, so
// that (u, v), (u+1, v), (u+1, v+1), (u, v+1) runs counter-clockwise seen from outside.
struct BoxSide {
  glm::ivec3 origin, du, dv;
  int nu, nv;
  glm::ivec3 at(int u, int v) const { return origin + u * du + v * dv; }
};

// A finger: a tube of 8 columns on the 2 x 2 block of `side` at (u0, v0), `rings` rings along
// `axis`, closed by a fan around a pole.
struct Finger {
  int u0, v0;
  glm::dvec3 axis;
  double length, radius;
};

void addFinger(PolyMesh& mesh, BoxSurface& box, const BoxSide& side, const Finger& finger, int rings) {
  // The block's boundary, counter-clockwise seen from outside.
  static const std::array<glm::ivec2, 8> kLoop = {{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  std::vector<Index> previous;
  glm::dvec3 centre = box.position(side.at(finger.u0 + 1, finger.v0 + 1));
  const glm::dvec3 axis = glm::normalize(finger.axis);
  std::array<glm::dvec3, 8> radial;
  for (size_t j = 0; j < 8; ++j) {
    const glm::ivec3 p = side.at(finger.u0 + kLoop[j].x, finger.v0 + kLoop[j].y);
    previous.push_back(box.vertex(p));
    const glm::dvec3 d = box.position(p) - centre;
    radial[j] = glm::normalize(d - glm::dot(d, axis) * axis);  // round tube from the square block
  }
  for (int r = 1; r <= rings; ++r) {
    const double t = double(r) / rings;
    const double radius = finger.radius * (1.0 - 0.15 * t);  // tapering towards the tip
    std::vector<Index> ring;
    for (size_t j = 0; j < 8; ++j) {
      ring.push_back(mesh.vertexCount());
      mesh.points.push_back(centre + finger.length * t * axis + radius * radial[j]);
    }
    for (size_t j = 0; j < 8; ++j) mesh.addFace({previous[j], previous[(j + 1) % 8], ring[(j + 1) % 8], ring[j]});
    previous = ring;
  }
  const Index pole = mesh.vertexCount();
  mesh.points.push_back(centre + (finger.length + 0.6 * finger.radius) * axis);
  for (size_t j = 0; j < 8; ++j) mesh.addFace({pole, previous[j], previous[(j + 1) % 8]});
}

}  // namespace

PolyMesh fingertips() {
  const glm::ivec3 n(13, 4, 6);
  PolyMesh mesh;
  BoxSurface box(mesh, n, glm::dvec3(0.25, 0.2, 0.4));
  // The six sides, du x dv outwards.
  const BoxSide top{{0, 0, n.z}, {1, 0, 0}, {0, 1, 0}, n.x, n.y};
  const BoxSide bottom{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, n.y, n.x};
  const BoxSide right{{n.x, 0, 0}, {0, 1, 0}, {0, 0, 1}, n.y, n.z};
  const BoxSide left{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, n.z, n.y};
  const BoxSide back{{0, n.y, 0}, {0, 0, 1}, {1, 0, 0}, n.z, n.x};
  const BoxSide front{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, n.x, n.z};
  // Four fingers on top (blocks at x = 1, 4, 7, 10), a thumb on the left side pointing out and up.
  struct Placed {
    const BoxSide* side;
    Finger finger;
  };
  const std::vector<Placed> fingers = {
      {&top, {1, 1, {0.1, 0.0, 1.0}, 1.4, 0.26}},  {&top, {4, 1, {0.0, 0.0, 1.0}, 1.8, 0.27}},
      {&top, {7, 1, {0.0, 0.0, 1.0}, 1.9, 0.27}},  {&top, {10, 1, {-0.1, 0.0, 1.0}, 1.7, 0.26}},
      {&left, {2, 1, {-1.0, 0.0, 0.7}, 1.3, 0.25}},
  };
  for (const BoxSide* side : {&top, &bottom, &right, &left, &back, &front})
    for (int v = 0; v < side->nv; ++v)
      for (int u = 0; u < side->nu; ++u) {
        bool open = false;  // inside a finger's block
        for (const Placed& f : fingers)
          open = open || (f.side == side && u - f.finger.u0 >= 0 && u - f.finger.u0 < 2 && v - f.finger.v0 >= 0 &&
                          v - f.finger.v0 < 2);
        if (open) continue;
        mesh.addFace({box.vertex(side->at(u, v)), box.vertex(side->at(u + 1, v)), box.vertex(side->at(u + 1, v + 1)),
                      box.vertex(side->at(u, v + 1))});
      }
  for (const Placed& f : fingers) addFinger(mesh, box, *f.side, f.finger, 5);
  return mesh;
}

}  // namespace polarview::shapes
