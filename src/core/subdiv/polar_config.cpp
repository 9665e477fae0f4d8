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

}  // namespace

std::vector<PolarConfig> findPolarConfigs(const PolyMesh& mesh, const MeshTopology& topo) {
  std::vector<PolarConfig> configs;
  std::vector<int> linkMark(topo.vertexCount, -1);  // which config's links claimed a vertex
  std::vector<Index> visitedBy(topo.vertexCount, -1);  // the pole whose walk reached a vertex: O(1) checks
  std::vector<Index> link1, fanFaces, inner, outer, innerFaces, outerFaces;

  for (Index v = 0; v < topo.vertexCount; ++v) {
    if (!topo.vertexUsed[v] || topo.vertexOnBoundary[v]) continue;
    if (topo.valence(v) < 3 || !allFacesHaveSize(mesh, topo, v, 3, nullptr)) continue;

    PolarConfig config;
    config.pole = v;
    config.valence = topo.valence(v);
    const int n = config.valence;

    // Link 1: the fan's rim, each a 4-valent interior vertex with two fan triangles and two quads.
    if (!orderFan(mesh, topo, v, link1, fanFaces, config)) { configs.push_back(config); continue; }
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
    config.links = link1;
    config.linkCount = 1;
    config.regularLinks = ok ? 1 : 0;
    if (!ok) { configs.push_back(config); continue; }

    // Walk outwards link by link: across each link edge, away from the pole, lies a quad of the
    // next ring, the fan of an opposite pole, a boundary, or irregular mesh.
    inner = link1;
    innerFaces = fanFaces;
    auto isVisited = [&](Index q) { return visitedBy[q] == v; };
    visitedBy[v] = v;
    for (Index q : link1) visitedBy[q] = v;
    while (true) {
      outer.assign(n, -1);
      outerFaces.assign(n, -1);
      int boundaryEdges = 0, triangles = 0;
      bool valid = true;
      Index capPole = -1;
      for (int j = 0; j < n && valid; ++j) {
        Index a = inner[j], b = inner[(j + 1) % n];
        Index e = topo.edgeBetween(a, b);
        if (e < 0) { valid = false; break; }
        if (topo.edgeOnBoundary(e)) { ++boundaryEdges; continue; }
        Index g = topo.faceAcross(e, innerFaces[j]);
        int ca = cornerOf(mesh, g, a);
        if (mesh.faceSize(g) == 3) {  // possibly the fan of an opposite pole
          Index p = mesh.face(g)[(ca + 1) % 3];
          if (triangles++ == 0) capPole = p;
          if (p != capPole) valid = false;
          continue;
        }
        if (mesh.faceSize(g) != 4) { valid = false; break; }
        // The quad runs (b, a, q_{i+1,j}, q_{i+1,j+1}).
        Index qa = mesh.face(g)[(ca + 1) % 4], qb = mesh.face(g)[(ca + 2) % 4];
        if (outer[j] >= 0 && outer[j] != qa) valid = false;
        outer[j] = qa;
        if (outer[(j + 1) % n] >= 0 && outer[(j + 1) % n] != qb) valid = false;
        outer[(j + 1) % n] = qb;
        outerFaces[j] = g;
      }
      if (boundaryEdges == n) { config.outer = PolarConfig::Outer::Boundary; break; }
      if (triangles == n && valid && capPole >= 0 && !isVisited(capPole) && topo.valence(capPole) == n &&
          allFacesHaveSize(mesh, topo, capPole, 3, nullptr)) {
        config.outer = PolarConfig::Outer::Pole;
        config.oppositePole = capPole;
        break;
      }
      if (!valid || boundaryEdges > 0 || triangles > 0) break;
      // A proper new link: distinct vertices never seen before.
      std::vector<Index> sorted = outer;
      std::sort(sorted.begin(), sorted.end());
      bool fresh = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
      for (int j = 0; j < n && fresh; ++j) fresh = !isVisited(outer[j]);
      if (!fresh) break;
      config.links.insert(config.links.end(), outer.begin(), outer.end());
      ++config.linkCount;
      for (Index q : outer) visitedBy[q] = v;
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
      inner = outer;
      innerFaces = outerFaces;
    }

    if (config.linkCount < 2) {
      reject(config, PolarRejection::NoLink2, "it has too few links (the 2-link is missing or not a ring of quads)");
    } else {
      config.refinable = true;
    }
    configs.push_back(config);
  }

  // Creases and corners (`t` tags): the polar rules have none, so a configuration whose pole or links
  // 1-3 carry one is left to Catmull-Clark; one carrying them further out ends before the first link
  // they touch (RTS and BPS refine every link radially, Catmull-Clark's rules take the creases).
  if (mesh.tags.hasSharpFeatures()) {
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
  if (const std::vector<uint8_t> holes = baseHoles(mesh, topo); !holes.empty()) {
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

  // Poles whose rule stencils (fan and 1-link) overlap cannot both be refined as poles.
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
  return configs;
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
