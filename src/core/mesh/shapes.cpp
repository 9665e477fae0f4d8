#include "core/mesh/shapes.h"

#include <algorithm>
#include <cmath>

#include "core/mesh/constants.h"

namespace polarview::shapes {

namespace {

// Adds the quads between two consecutive rings of n vertices starting at `inner` and `outer`.
void addRingQuads(PolyMesh& mesh, Index inner, Index outer, int n) {
  for (int j = 0; j < n; ++j) {
    int jn = (j + 1) % n;
    mesh.addFace({inner + j, outer + j, outer + jn, inner + jn});
  }
}
}  // namespace

PolyMesh revolvePoles(int n, int links, const std::function<void(double, double&, double&)>& profile) {
  PolyMesh mesh;
  double rho = 0, z = 0;
  profile(0.0, rho, z);
  mesh.points.push_back({0.0, 0.0, z});
  for (int i = 1; i <= links; ++i) {
    profile(double(i) / (links + 1), rho, z);
    for (int j = 0; j < n; ++j) {
      double a = kTwoPi * j / n;
      mesh.points.push_back({rho * std::cos(a), rho * std::sin(a), z});
    }
  }
  profile(1.0, rho, z);
  mesh.points.push_back({0.0, 0.0, z});
  const Index top = 0, bottom = mesh.vertexCount() - 1;
  auto ringStart = [&](int i) { return Index(1 + (i - 1) * n); };
  // Top pole seen from above (+z): columns run counter-clockwise, so (pole, q1j, q1j+1) faces up.
  for (int j = 0; j < n; ++j) mesh.addFace({top, ringStart(1) + j, ringStart(1) + (j + 1) % n});
  for (int i = 1; i < links; ++i) addRingQuads(mesh, ringStart(i), ringStart(i + 1), n);
  for (int j = 0; j < n; ++j) mesh.addFace({bottom, ringStart(links) + (j + 1) % n, ringStart(links) + j});
  return mesh;
}

PolyMesh globe(int n, int links, double radius) {
  return revolvePoles(n, links, [radius](double t, double& rho, double& z) {
    rho = radius * std::sin(t * kTwoPi / 2);
    z = radius * std::cos(t * kTwoPi / 2);
  });
}

PolyMesh polarCap(int n, int links, double radius, double curvature) {
  return heightCap(n, links, [curvature](double x, double y) { return 0.5 * curvature * (x * x + y * y); }, radius);
}

PolyMesh heightCap(int n, int links, const std::function<double(double, double)>& height, double radius) {
  PolyMesh mesh;
  mesh.points.push_back({0.0, 0.0, height(0.0, 0.0)});
  for (int i = 1; i <= links; ++i) {
    double r = radius * i / links;
    for (int j = 0; j < n; ++j) {
      double a = kTwoPi * j / n;
      const double x = r * std::cos(a), y = r * std::sin(a);
      mesh.points.push_back({x, y, height(x, y)});
    }
  }
  for (int j = 0; j < n; ++j) mesh.addFace({0, 1 + j, 1 + (j + 1) % n});
  for (int i = 1; i < links; ++i) addRingQuads(mesh, 1 + (i - 1) * n, 1 + i * n, n);
  return mesh;
}

std::function<double(double, double)> paperHeight(const std::string& name) {
  if (name == "paraboloid") return [](double x, double y) { return 0.5 * (x * x + y * y); };
  if (name == "saddle") return [](double x, double y) { return 0.5 * (x * x - y * y); };
  if (name == "monkey") return [](double x, double y) { return x * x * x - 3.0 * x * y * y; };
  if (name == "flat4") return [](double x, double y) { return (x * x + y * y) * (x * x + y * y); };
  if (name == "saddle4") return [](double x, double y) { return x * x * x * x - 6.0 * x * x * y * y + y * y * y * y; };
  // Fig. 11's cone: a sharp tip whose first ring is far from C2PS's limit (K rises steeply to the
  // pole), where C2PS applied directly makes K wave along the spokes and the uniform first step does not.
  if (name == "cone") return [](double x, double y) { return -0.7 * std::sqrt(x * x + y * y); };
  // Fig. 4's convex configuration: a dome steep at its rim, where Catmull-Clark ripples.
  if (name == "convex") return [](double x, double y) { return 0.5 * std::sqrt(std::max(0.0, 1.0 - 0.95 * (x * x + y * y))); };
  return nullptr;
}

PolyMesh mushroom(int n) {
  const int k = n / 4;  // bottom grid is k x k, its boundary has 4k = n vertices
  // Profile from the pole down: a domed cap, its rim folding under, then a narrow stem.
  const double capR[] = {0.55, 1.0, 1.25, 1.3, 1.1, 0.45, 0.38, 0.38, 0.40};
  const double capZ[] = {1.55, 1.35, 1.0, 0.65, 0.4, 0.45, 0.0, -0.6, -1.1};
  const int links = int(sizeof(capR) / sizeof(capR[0]));
  PolyMesh mesh;
  mesh.points.push_back({0.0, 0.0, 1.65});
  for (int i = 0; i < links; ++i)
    for (int j = 0; j < n; ++j) {
      double a = kTwoPi * j / n;
      mesh.points.push_back({capR[i] * std::cos(a), capR[i] * std::sin(a), capZ[i]});
    }
  auto ring = [&](int i) { return Index(1 + (i - 1) * n); };
  for (int j = 0; j < n; ++j) mesh.addFace({0, ring(1) + j, ring(1) + (j + 1) % n});
  for (int i = 1; i < links; ++i) addRingQuads(mesh, ring(i), ring(i + 1), n);

  // Bottom: a k x k grid whose boundary is the last ring. Map ring index j to the square's
  // boundary walked so that the bottom faces point down (-z).
  const Index last = ring(links);
  const double bottomZ = -1.25, half = 0.30;
  std::vector<Index> gridId((k + 1) * (k + 1), -1);
  auto boundaryIndex = [&](int a, int b) -> int {  // position of grid node (a,b) on the boundary, or -1
    if (b == 0) return a;                     // bottom side, a = 0..k
    if (a == k) return k + b;                 // right side
    if (b == k) return 3 * k - a;             // top side
    if (a == 0) return (4 * k - b) % (4 * k); // left side
    return -1;
  };
  // Angle of ring vertex j is 2 pi j / n; start the square walk at angle -135 deg (corner) so
  // corners line up with ring vertices j = n/8 * odd... keep it simple: rotate the walk by 3k/2.
  const int shift = (5 * k) / 2;
  for (int b = 0; b <= k; ++b)
    for (int a = 0; a <= k; ++a) {
      int bi = boundaryIndex(a, b);
      if (bi >= 0) {
        gridId[b * (k + 1) + a] = last + (bi + shift) % n;
      } else {
        gridId[b * (k + 1) + a] = mesh.vertexCount();
        mesh.points.push_back({-half + 2 * half * a / k, -half + 2 * half * b / k, bottomZ});
      }
    }
  for (int b = 0; b < k; ++b)
    for (int a = 0; a < k; ++a) {
      Index v00 = gridId[b * (k + 1) + a], v10 = gridId[b * (k + 1) + a + 1];
      Index v11 = gridId[(b + 1) * (k + 1) + a + 1], v01 = gridId[(b + 1) * (k + 1) + a];
      mesh.addFace({v00, v01, v11, v10});  // clockwise seen from +z: faces down
    }
  return mesh;
}

PolyMesh cube() {
  PolyMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.points.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  mesh.addFace({0, 2, 3, 1});  // z = 0, facing -z
  mesh.addFace({4, 5, 7, 6});  // z = 1
  mesh.addFace({0, 1, 5, 4});  // y = 0
  mesh.addFace({2, 6, 7, 3});  // y = 1
  mesh.addFace({0, 4, 6, 2});  // x = 0
  mesh.addFace({1, 3, 7, 5});  // x = 1
  return mesh;
}

PolyMesh ngonCylinder(int n) {
  PolyMesh mesh;
  for (double z : {-1.0, 1.0})
    for (int i = 0; i < n; ++i) mesh.points.push_back({std::cos(kTwoPi * i / n), std::sin(kTwoPi * i / n), z});
  for (int i = 0; i < n; ++i) mesh.addFace({i, (i + 1) % n, n + (i + 1) % n, n + i});
  std::vector<Index> top, bottom;  // counter-clockwise seen from outside: the bottom runs backwards
  for (int i = 0; i < n; ++i) top.push_back(n + i), bottom.push_back(n - 1 - i);
  mesh.addFace(top.data(), top.size());
  mesh.addFace(bottom.data(), bottom.size());
  return mesh;
}

PolyMesh torus(int nu, int nv, double majorRadius, double minorRadius) {
  PolyMesh mesh;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      double a = kTwoPi * i / nu, b = kTwoPi * j / nv;
      double rho = majorRadius + minorRadius * std::cos(b);
      mesh.points.push_back({rho * std::cos(a), rho * std::sin(a), minorRadius * std::sin(b)});
    }
  auto id = [&](int i, int j) { return Index(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) mesh.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return mesh;
}

PolyMesh grid(int nu, int nv, const std::function<double(double, double)>& height) {
  PolyMesh mesh;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      double x = double(i) / nu, y = double(j) / nv;
      mesh.points.push_back({x, y, height ? height(x, y) : 0.0});
    }
  auto id = [&](int i, int j) { return Index(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) mesh.addFace({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return mesh;
}

}  // namespace polarview::shapes
