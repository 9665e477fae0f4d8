// What `polarview info` reports on a mesh (poles, rejected pole candidates, extraordinary vertices,
// boundaries), made once and written as the CLI's text or as JSON; the Python module's Mesh.info()
// converts the same tree (meshInfoValue) the JSON is printed from.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/mesh/manifold_split.h"
#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/scheme.h"
#include "pipeline/report_value.h"

namespace polarview {

// Catmull-Clark extraordinary vertices: interior valence != 4, boundary valence > 3.
struct Extraordinary {
  Index vertex;
  int valence;
  bool boundary;
  bool pole;
};

// What `info` reports on a mesh (the split mesh's counts where the input is non-manifold).
struct MeshReport {
  std::vector<PolarConfig> poles, rejected;  // poles a polar scheme refines; vertices that only look polar
  std::map<PolarRejection, int> rejectedPerReason;
  bool radialMesh = false;  // RTS/BPS refine the whole mesh radially (caps and globes)
  int used = 0, copies = 0, triangles = 0, quads = 0, polygons = 0, holeFaces = 0, loops = 0;
  int fanFaces = 0;  // faces convert --ngon-to-fan would make triangle fans
  std::vector<Extraordinary> extraordinary;
};

// "pole", "boundary" or "mesh": where a configuration's links end. [O(1)]
const char* outerName(PolarConfig::Outer outer);
// What `scheme` does at a polar configuration, in words. [O(1)]
std::string schemeAction(Scheme scheme, const PolarConfig& c, bool radialMesh);
// Number of boundary loops: connected components of the boundary edges. [O(mesh)]
int countBoundaryLoops(const MeshTopology& topo);
// The report on `mesh` (refinableMesh of `input`, with its tables `topo`). [O(mesh)]
MeshReport reportMesh(const PolyMesh& input, const PolyMesh& mesh, const MeshTopology& topo);
// `info --json`'s object as a tree. [O(mesh)]
ReportValue meshInfoValue(const std::string& file, const PolyMesh& mesh, const MeshTopology& topo, const ManifoldSplit& split,
                          const MeshReport& r);
// ... and as `info --json` prints it (one line, numbers round-trip). [O(mesh)]
std::string meshInfoJson(const std::string& file, const PolyMesh& mesh, const MeshTopology& topo, const ManifoldSplit& split,
                         const MeshReport& r);
// The tree from the input alone: split where non-manifold, tables built, reported. Throws
// InputError naming `file` for meshes refinableMesh refuses. [O(mesh)]
ReportValue meshInfoValue(const std::string& file, const PolyMesh& input);

}  // namespace polarview
