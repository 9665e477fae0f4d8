// libFuzzer target over polar detection (tests/fuzz/README.md): small OBJ inputs -> refinableMesh
// (the manifold split where needed) -> findPolarConfigs, refinable and rejected candidates alike.
//
// Expected: polarview::InputError from the reader or the tables. A finding: any other exception, a
// crash, ASan/UBSan report, a hang, or a broken guarantee of polar_config.h:
//  * the configurations are exactly the candidates, well formed, a refinable one with valence >= 3,
//    >= 2 links, ids in range and distinct, its fan and links made of the mesh's faces and edges,
//    no tag on it, apart from the other poles (checkPolarConfigs in fuzz_common.h);
//  * on a manifold mesh, detection does not depend on where each face's loop starts or on which
//    way all faces wind: with every loop started at its next corner, and with every loop reversed,
//    each vertex gets the same outcome (refinable or the same rejection, the three of the 1-link
//    counting as one; valence, links, regular links, outer end, opposite pole) and the same set of
//    vertices in each link.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/input_error.h"
#include "core/mesh/manifold_split.h"
#include "core/mesh/topology.h"
#include "core/subdiv/polar_config.h"
#include "fuzz_common.h"
#include "obj_mutator.h"

using namespace polarview;
using namespace polarview::fuzz;

namespace {

constexpr InputLimits kLimits{16 << 10, 1000, 2000};

// A copy of `mesh` whose face loops start one corner later (rotate) or run the other way from the
// same first corner (reverse).
PolyMesh transformed(const PolyMesh& mesh, bool reverse) {
  PolyMesh out = mesh;
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    auto begin = out.faceVerts.begin() + mesh.faceStart[size_t(f)], end = out.faceVerts.begin() + mesh.faceStart[size_t(f) + 1];
    if (reverse)
      std::reverse(begin + 1, end);
    else
      std::rotate(begin, begin + 1, end);
  }
  return out;
}

std::string describe(const PolarConfig& c) {
  return "pole " + std::to_string(c.pole) + " (valence " + std::to_string(c.valence) + ", " + std::to_string(c.linkCount) + " links, " +
         std::to_string(c.regularLinks) + " regular, outer " + std::to_string(int(c.outer)) + ", opposite " + std::to_string(c.oppositePole) +
         ", " + polarRejectionKey(c.rejection) + ")";
}

// The rejection, with the three of the 1-link as one: which applies is that of the first offending
// 1-link vertex, which depends on where the fan starts and which way it runs.
PolarRejection rejectionClass(PolarRejection r) {
  return r == PolarRejection::Link1NotFourValent || r == PolarRejection::Link1NotTwoQuads ? PolarRejection::Link1OnBoundary : r;
}

void compareConfigs(const std::vector<PolarConfig>& a, const std::vector<PolarConfig>& b, const char* how) {
  if (a.size() != b.size()) fail(std::to_string(b.size()) + " polar configurations with " + how + ", " + std::to_string(a.size()) + " without");
  std::vector<Index> ringA, ringB;
  for (size_t k = 0; k < a.size(); ++k) {
    const PolarConfig &x = a[k], &y = b[k];
    if (x.pole != y.pole || x.valence != y.valence || x.linkCount != y.linkCount || x.regularLinks != y.regularLinks ||
        x.outer != y.outer || x.oppositePole != y.oppositePole || x.refinable != y.refinable ||
        rejectionClass(x.rejection) != rejectionClass(y.rejection))
      fail(describe(y) + " with " + how + ", " + describe(x) + " without");
    for (int i = 0; i < x.linkCount; ++i) {
      const size_t from = size_t(i) * size_t(x.valence), to = from + size_t(x.valence);
      ringA.assign(x.links.begin() + long(from), x.links.begin() + long(to));
      ringB.assign(y.links.begin() + long(from), y.links.begin() + long(to));
      std::sort(ringA.begin(), ringA.end()), std::sort(ringB.begin(), ringB.end());
      if (ringA != ringB) fail("link " + std::to_string(i + 1) + " of pole " + std::to_string(x.pole) + " has other vertices with " + how);
    }
  }
}

void run(const uint8_t* data, size_t size) {
  PolyMesh mesh;
  if (!parseInput(data, size, kLimits, mesh)) return;
  gStage = "refinableMesh";
  ManifoldSplit split;
  MeshTopology topology;
  const PolyMesh& refinable = refinableMesh(mesh, split, topology, kSource);  // InputError: not refinable

  gStage = "findPolarConfigs";
  const std::vector<PolarConfig> configs = findPolarConfigs(refinable, topology);
  checkPolarConfigs(refinable, topology, configs);
  if (!split.empty()) return;  // the split's copies are numbered by corner order

  for (const bool reverse : {false, true}) {
    const char* how = reverse ? "every face reversed" : "every face started at its next corner";
    gStage = std::string("findPolarConfigs with ") + how;
    const PolyMesh other = transformed(mesh, reverse);
    MeshTopology otherTopology;
    try {
      otherTopology = buildTopology(other, kSource);
    } catch (const InputError& e) {
      fail(std::string("buildTopology refuses the mesh with ") + how + ": " + e.what());
    }
    const std::vector<PolarConfig> otherConfigs = findPolarConfigs(other, otherTopology);
    checkPolarConfigs(other, otherTopology, otherConfigs);
    compareConfigs(configs, otherConfigs, how);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return runInput([&] { run(data, size); });
}
