#include "core/subdiv/polar_config.h"

#include <algorithm>
#include <utility>

#include "core/subdiv/catmull_clark.h"

namespace polarview {

namespace {

// The corner of face f that holds vertex v, or -1. [O(face size)]
int cornerOf(const PolyMesh& mesh, Index f, Index v) {
  for (int c = 0; c < mesh.faceSize(f); ++c)
    if (mesh.face(f)[c] == v) return c;
  return -1;
}

bool allFacesHaveSize(const PolyMesh& mesh, const MeshTopology& topo, Index v, int size, int* count) {
  int n = 0;
  for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k)
    n += mesh.faceSize(topo.vertexFaces[k]) == size;
  if (count) *count = n;
  return n == topo.faceValence(v);
}

std::string vertexName(Index v) { return "vertex " + std::to_string(v); }

// Marks `config` as not refinable, with the kind and the sentence. Always returns false.
bool reject(PolarConfig& config, PolarRejection rejection, std::string reason) {
  config.refinable = false;
  config.rejection = rejection;
  config.reason = std::move(reason);
  return false;
}

// Orders the fan around `pole` so that triangles (pole, q_{1j}, q_{1,j+1}) follow the face winding,
// from the topology's rotational face order (walked forwards or backwards). Returns false (and
// rejects `config`) when the fan is not a simple cycle. [O(n)]
bool orderFan(const PolyMesh& mesh, const MeshTopology& topo, Index pole, std::vector<Index>& link1,
              std::vector<Index>& fanFaces, PolarConfig& config) {
  const Index n = topo.faceValence(pole);
  const Index first = topo.vertexFaceStart[pole];
  // (a, b): the corners after the pole in face k's winding.
  auto corner = [&](Index k, int step) {
    Index f = topo.vertexFaces[first + k];
    int c = cornerOf(mesh, f, pole);
    return mesh.face(f)[(c + step) % 3];
  };
  bool forward = corner(0, 2) == corner(1 % n, 1);
  link1.assign(n, -1);
  fanFaces.assign(n, -1);
  for (Index j = 0; j < n; ++j) {
    Index k = forward ? j : (n - j) % n;
    link1[j] = corner(k, 1);
    fanFaces[j] = topo.vertexFaces[first + k];
  }
  for (Index j = 0; j < n; ++j) {
    Index k = forward ? j : (n - j) % n;
    if (corner(k, 2) != link1[(j + 1) % n])
      return reject(config, PolarRejection::FanNotCycle, "its fan is not a closed cycle of triangles");
  }
  std::vector<Index> sorted = link1;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    return reject(config, PolarRejection::FanRepeatsVertex, "its fan visits a vertex twice");
  return true;
}

// Link 1: the fan's rim, each a 4-valent interior vertex with two fan triangles and two quads.
// Returns false (and rejects `config`) at the first vertex that is not. [O(n)]
bool checkLink1(const PolyMesh& mesh, const MeshTopology& topo, const std::vector<Index>& link1, PolarConfig& config) {
  bool ok = true;
  for (Index q : link1) {
    int quads = 0;
    allFacesHaveSize(mesh, topo, q, 4, &quads);
    if (topo.vertexOnBoundary[q])
      ok = reject(config, PolarRejection::Link1OnBoundary, "its 1-link vertex " + std::to_string(q) + " is on a boundary");
    else if (topo.valence(q) != 4)
      ok = reject(config, PolarRejection::Link1NotFourValent,
                  "its 1-link has a " + std::to_string(topo.valence(q)) + "-valent vertex (" + vertexName(q) + ")");
    else if (quads != 2)
      ok = reject(config, PolarRejection::Link1NotTwoQuads,
                  "its 1-link vertex " + std::to_string(q) + " is not surrounded by 2 triangles and 2 quads");
    if (!ok) break;
  }
  return ok;
}

// The buffers of the walk outwards, kept across candidates so that a mesh of many candidates
// allocates them once. visitedBy[q] is the pole whose walk reached vertex q: O(1) checks.
struct LinkWalk {
  std::vector<Index> visitedBy;
  std::vector<Index> link1, fanFaces, inner, outer, innerFaces, outerFaces;
};

// What lies across each edge of a link, away from the pole.
struct AcrossLink {
  int boundaryEdges = 0;  // link edges on a boundary
  int triangles = 0;      // triangles across link edges (the fan of an opposite pole, if all agree)
  bool valid = true;      // false: irregular mesh, or quads that disagree on the next link
  Index capPole = -1;     // the apex of the first triangle across
};

// Steps across link `walk.inner` (whose faces towards the pole are `walk.innerFaces`): fills
// `walk.outer` with the next link's vertices q_{i+1,j} and `walk.outerFaces` with the quads between,
// where quads lie across. [O(n)]
AcrossLink stepAcrossLink(const PolyMesh& mesh, const MeshTopology& topo, int n, LinkWalk& walk) {
  std::vector<Index>& outer = walk.outer;
  outer.assign(n, -1);
  walk.outerFaces.assign(n, -1);
  AcrossLink across;
  for (int j = 0; j < n && across.valid; ++j) {
    Index a = walk.inner[j], b = walk.inner[(j + 1) % n];
    Index e = topo.edgeBetween(a, b);
    if (e < 0) { across.valid = false; break; }
    if (topo.edgeOnBoundary(e)) { ++across.boundaryEdges; continue; }
    Index g = topo.faceAcross(e, walk.innerFaces[j]);
    int ca = cornerOf(mesh, g, a);
    if (mesh.faceSize(g) == 3) {  // possibly the fan of an opposite pole
      Index p = mesh.face(g)[(ca + 1) % 3];
      if (across.triangles++ == 0) across.capPole = p;
      if (p != across.capPole) across.valid = false;
      continue;
    }
    if (mesh.faceSize(g) != 4) { across.valid = false; break; }
    // The quad runs (b, a, q_{i+1,j}, q_{i+1,j+1}).
    Index qa = mesh.face(g)[(ca + 1) % 4], qb = mesh.face(g)[(ca + 2) % 4];
    if (outer[j] >= 0 && outer[j] != qa) across.valid = false;
    outer[j] = qa;
    if (outer[(j + 1) % n] >= 0 && outer[(j + 1) % n] != qb) across.valid = false;
    outer[(j + 1) % n] = qb;
    walk.outerFaces[j] = g;
  }
  return across;
}

// Walks outwards from link 1 link by link: across each link edge, away from the pole, lies a quad
// of the next ring, the fan of an opposite pole, a boundary, or irregular mesh. Appends the links
// found to `config` and sets how the region ends. [O(region)]
void walkLinks(const PolyMesh& mesh, const MeshTopology& topo, PolarConfig& config, LinkWalk& walk) {
  const Index v = config.pole;
  const int n = config.valence;
  walk.inner = walk.link1;
  walk.innerFaces = walk.fanFaces;
  auto isVisited = [&](Index q) { return walk.visitedBy[q] == v; };
  walk.visitedBy[v] = v;
  for (Index q : walk.link1) walk.visitedBy[q] = v;
  while (true) {
    const AcrossLink across = stepAcrossLink(mesh, topo, n, walk);
    const Index capPole = across.capPole;
    if (across.boundaryEdges == n) { config.outer = PolarConfig::Outer::Boundary; break; }
    if (across.triangles == n && across.valid && capPole >= 0 && !isVisited(capPole) && topo.valence(capPole) == n &&
        allFacesHaveSize(mesh, topo, capPole, 3, nullptr)) {
      config.outer = PolarConfig::Outer::Pole;
      config.oppositePole = capPole;
      break;
    }
    if (!across.valid || across.boundaryEdges > 0 || across.triangles > 0) break;
    // A proper new link: distinct vertices never seen before.
    const std::vector<Index>& outer = walk.outer;
    std::vector<Index> sorted = outer;
    std::sort(sorted.begin(), sorted.end());
    bool fresh = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
    for (int j = 0; j < n && fresh; ++j) fresh = !isVisited(outer[j]);
    if (!fresh) break;
    config.links.insert(config.links.end(), outer.begin(), outer.end());
    ++config.linkCount;
    for (Index q : outer) walk.visitedBy[q] = v;
    // Keep walking only through regular links (4-valent interior vertices among quads); an
    // irregular link is the last one the configuration owns.
    bool regular = true;
    for (Index q : outer)
      regular = regular && !topo.vertexOnBoundary[q] && topo.valence(q) == 4 && allFacesHaveSize(mesh, topo, q, 4, nullptr);
    if (!regular) {
      // A ring that only borders an opposite fan or a boundary is still regular enough for the walk.
      bool nextToEnd = true;
      for (Index q : outer) nextToEnd = nextToEnd && topo.valence(q) <= 4;
      if (!nextToEnd) break;
    } else {
      config.regularLinks = config.linkCount;
    }
    walk.inner = walk.outer;
    walk.innerFaces = walk.outerFaces;
  }
}

// The configuration around polar-looking vertex v (interior, valence >= 3, all triangles):
// refinable, or rejected with the reason. [O(region)]
PolarConfig polarConfigAt(const PolyMesh& mesh, const MeshTopology& topo, Index v, LinkWalk& walk) {
  PolarConfig config;
  config.pole = v;
  config.valence = topo.valence(v);

  if (!orderFan(mesh, topo, v, walk.link1, walk.fanFaces, config)) return config;
  const bool ok = checkLink1(mesh, topo, walk.link1, config);
  config.links = walk.link1;
  config.linkCount = 1;
  config.regularLinks = ok ? 1 : 0;
  if (!ok) return config;

  walkLinks(mesh, topo, config, walk);
  if (config.linkCount < 2) {
    reject(config, PolarRejection::NoLink2, "it has too few links (the 2-link is missing or not a ring of quads)");
  } else {
    config.refinable = true;
  }
  return config;
}

// Creases and corners (`t` tags): the polar rules have none, so a configuration whose pole or links
// 1-3 carry one is left to Catmull-Clark; one carrying them further out ends before the first link
// they touch (RTS and BPS refine every link radially, Catmull-Clark's rules take the creases).
void applySharpFeatures(const PolyMesh& mesh, const MeshTopology& topo, std::vector<PolarConfig>& configs) {
  std::vector<uint8_t> sharp(size_t(topo.vertexCount), 0);
  for (const CreaseEdge& crease : mesh.tags.creases)
    if (crease.sharpness > 0.0) sharp[size_t(crease.v0)] = sharp[size_t(crease.v1)] = 1;
  for (const CornerVertex& corner : mesh.tags.corners)
    if (corner.sharpness > 0.0) sharp[size_t(corner.vertex)] = 1;
  for (PolarConfig& config : configs) {
    if (!config.refinable) continue;
    Index tagged = sharp[size_t(config.pole)] ? config.pole : -1;
    const size_t count = size_t(std::min(config.linkCount, 3)) * size_t(config.valence);
    for (size_t k = 0; k < count && k < config.links.size() && tagged < 0; ++k)
      if (sharp[size_t(config.links[k])]) tagged = config.links[k];
    if (tagged >= 0) {
      reject(config, PolarRejection::SharpFeature,
             "a crease or corner tag touches it at vertex " + std::to_string(tagged) + " (the polar rules have none)");
      continue;
    }
    for (int link = 4; link <= config.linkCount; ++link) {
      bool touched = false;
      for (int j = 0; j < config.valence && !touched; ++j) touched = sharp[size_t(config.links[size_t(link - 1) * config.valence + j])];
      if (!touched) continue;
      config.linkCount = link - 1;
      config.links.resize(size_t(config.linkCount) * size_t(config.valence));
      config.regularLinks = std::min(config.regularLinks, config.linkCount);
      config.outer = PolarConfig::Outer::Mesh;
      config.oppositePole = -1;
      break;
    }
  }
}

// Holes (`t hole`, `t interpolateboundary 0`): the caps would close over them, so a configuration
// with a hole at its pole or links 1-3 is left to Catmull-Clark (whose patches skip holes).
void rejectHoles(const MeshTopology& topo, const std::vector<uint8_t>& holes, std::vector<PolarConfig>& configs) {
  auto touchesHole = [&](Index v) {
    for (Index k = topo.vertexFaceStart[v]; k < topo.vertexFaceStart[v + 1]; ++k)
      if (holes[size_t(topo.vertexFaces[k])]) return true;
    return false;
  };
  for (PolarConfig& config : configs) {
    if (!config.refinable) continue;
    Index at = touchesHole(config.pole) ? config.pole : -1;
    const size_t count = size_t(std::min(config.linkCount, 3)) * size_t(config.valence);
    for (size_t k = 0; k < count && k < config.links.size() && at < 0; ++k)
      if (touchesHole(config.links[k])) at = config.links[k];
    if (at >= 0) reject(config, PolarRejection::Hole, "a hole face touches it at vertex " + std::to_string(at));
  }
}

// Poles whose rule stencils (fan and 1-link) overlap cannot both be refined as poles: the first in
// vertex order keeps its stencil.
void rejectOverlappingStencils(const MeshTopology& topo, std::vector<PolarConfig>& configs) {
  std::vector<int> linkMark(topo.vertexCount, -1);  // which config's stencil claimed a vertex
  for (size_t k = 0; k < configs.size(); ++k) {
    PolarConfig& config = configs[k];
    if (!config.refinable) continue;
    int clash = linkMark[config.pole];
    for (int j = 0; j < config.valence && clash < 0; ++j) clash = linkMark[config.links[j]];
    if (clash >= 0) {
      reject(config, PolarRejection::StencilOverlap,
             "its stencil overlaps the pole at vertex " + std::to_string(configs[size_t(clash)].pole));
      continue;
    }
    linkMark[config.pole] = int(k);
    for (int j = 0; j < config.valence; ++j) linkMark[config.links[j]] = int(k);
  }
}

}  // namespace

std::vector<PolarConfig> findPolarConfigs(const PolyMesh& mesh, const MeshTopology& topo) {
  std::vector<PolarConfig> configs;
  LinkWalk walk;
  walk.visitedBy.assign(topo.vertexCount, -1);
  for (Index v = 0; v < topo.vertexCount; ++v) {
    if (!topo.vertexUsed[v] || topo.vertexOnBoundary[v]) continue;
    if (topo.valence(v) < 3 || !allFacesHaveSize(mesh, topo, v, 3, nullptr)) continue;
    configs.push_back(polarConfigAt(mesh, topo, v, walk));
  }
  if (mesh.tags.hasSharpFeatures()) applySharpFeatures(mesh, topo, configs);
  if (const std::vector<uint8_t> holes = baseHoles(mesh, topo); !holes.empty()) rejectHoles(topo, holes, configs);
  rejectOverlappingStencils(topo, configs);
  return configs;
}

bool nearerPolarCandidate(const PolarConfig& a, const PolarConfig& b) {
  if (a.valence != b.valence) return a.valence > b.valence;
  if (a.rejection != b.rejection) return a.rejection > b.rejection;
  return a.pole < b.pole;
}

std::vector<RejectedGroup> groupRejectedCandidates(const std::vector<PolarConfig>& configs) {
  std::vector<size_t> order;
  for (size_t k = 0; k < configs.size(); ++k)
    if (!configs[k].refinable) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return nearerPolarCandidate(configs[a], configs[b]); });
  // Walking nearest first, a kind's group is made where its nearest candidate comes.
  std::vector<RejectedGroup> groups;
  for (size_t k : order) {
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const RejectedGroup& g) { return g.rejection == configs[k].rejection; });
    if (group == groups.end()) group = groups.insert(groups.end(), RejectedGroup{configs[k].rejection, {}});
    group->members.push_back(k);
  }
  return groups;
}

const char* polarRejectionKey(PolarRejection rejection) {
  switch (rejection) {
    case PolarRejection::None: return "none";
    case PolarRejection::FanNotCycle: return "fan_not_closed";
    case PolarRejection::FanRepeatsVertex: return "fan_repeats_vertex";
    case PolarRejection::Link1OnBoundary: return "link1_on_boundary";
    case PolarRejection::Link1NotFourValent: return "link1_not_4_valent";
    case PolarRejection::Link1NotTwoQuads: return "link1_not_2_triangles_2_quads";
    case PolarRejection::NoLink2: return "no_link2";
    case PolarRejection::StencilOverlap: return "stencil_overlap";
    case PolarRejection::SharpFeature: return "sharp_feature";
    case PolarRejection::Hole: return "hole";
  }
  return "?";
}

const char* polarRejectionWords(PolarRejection rejection) {
  switch (rejection) {
    case PolarRejection::None: return "refinable";
    case PolarRejection::FanNotCycle: return "the fan is not a closed cycle";
    case PolarRejection::FanRepeatsVertex: return "the fan visits a vertex twice";
    case PolarRejection::Link1OnBoundary: return "a 1-link vertex is on a boundary";
    case PolarRejection::Link1NotFourValent: return "a 1-link vertex is not 4-valent";
    case PolarRejection::Link1NotTwoQuads: return "a 1-link vertex is not between 2 triangles and 2 quads";
    case PolarRejection::NoLink2: return "no 2-link (ring of quads)";
    case PolarRejection::StencilOverlap: return "its stencil overlaps another pole's";
    case PolarRejection::SharpFeature: return "a crease or corner tag touches it";
    case PolarRejection::Hole: return "a hole face touches it";
  }
  return "?";
}

bool schemeRefinesPole(Scheme scheme, const PolarConfig& config, std::string* reason) {
  auto refuse = [&](const std::string& why) {
    if (reason) *reason = why;
    return false;
  };
  const SchemeTraits& traits = schemeTraits(scheme);
  if (!traits.polar()) return refuse("Catmull-Clark has no polar rules");
  if (!config.refinable) return refuse(config.reason);
  if (config.valence < traits.minValence)
    return refuse(std::string(traits.name) + " needs valence >= " + std::to_string(traits.minValence) +
                  " (its weights alias below)");
  return true;
}

}  // namespace polarview
