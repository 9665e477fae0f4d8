// Fig. 1's eigenvector nets (see eigen_nets.h).
#include "pipeline/eigen_nets.h"

#include <cmath>
#include <vector>

#include "core/mesh/shapes.h"
#include "core/subdiv/polar_grid.h"
#include "core/subdiv/spectrum.h"

namespace polarview {

PolyMesh eigenNet(int n, int k, int steps) {
  constexpr int kLinks = 5;  // the support of matrix (13)
  constexpr double kHeight = 0.6, kDiskDepth = -1.2;  // drawing scale of v_k and where chi lies
  const std::vector<EigenPair> pairs = schemeEigenPairs(Scheme::RTS, n, 6);
  const EigenPair& pair = pairs.at(size_t(k));
  PolarGrid grid(n, kLinks);
  auto entry = [&](const EigenPair& p, int i, int j) { return p.right[size_t(polarMatrixIndex(i, j))].real(); };
  grid.pole = Point(entry(pairs[1], 0, 0), entry(pairs[2], 0, 0), k >= 3 ? entry(pair, 0, 0) : 0.0);
  for (int i = 1; i <= kLinks; ++i)
    for (int j = 0; j < n; ++j) grid.q(i, j) = Point(entry(pairs[1], i, j), entry(pairs[2], i, j), k >= 3 ? entry(pair, i, j) : 0.0);
  for (int step = 0; step < steps; ++step) grid = c2psStepOnLinks(grid);
  const double xy = std::ldexp(1.0, steps), z = kHeight * std::pow(1.0 / pair.value.real(), steps);
  auto place = [&](const Point& p) { return Point(xy * p.x, xy * p.y, z * p.z); };
  PolyMesh mesh = shapes::heightCap(grid.n, kLinks, [](double, double) { return 0.0; });  // the layout
  mesh.points[0] = place(grid.pole);
  for (int i = 1; i <= kLinks; ++i)
    for (int j = 0; j < grid.n; ++j) mesh.points[size_t(1 + (i - 1) * grid.n + j)] = place(grid.q(i, j));
  if (k < 3 || steps > 0) return mesh;
  PolyMesh both = mesh;  // chi's disk below: the same net flattened, a second component
  const Index offset = Index(both.points.size());
  for (const Point& p : mesh.points) both.points.push_back(Point(p.x, p.y, kDiskDepth));
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    std::vector<Index> loop(mesh.face(f), mesh.face(f) + mesh.faceSize(f));
    for (Index& v : loop) v += offset;
    both.addFace(loop.data(), loop.size());
  }
  return both;
}

}  // namespace polarview
