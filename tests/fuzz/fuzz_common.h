// Shared by the libFuzzer targets here (README.md): how a finding is reported, how an input
// becomes a mesh, and the checks more than one target makes (the reader's guarantees, the tags',
// the polar configurations'). Each target is one translation unit: everything here is inline.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/poly_mesh.h"
#include "core/mesh/topology.h"
#include "core/subdiv/catmull_clark.h"
#include "core/subdiv/polar_config.h"
#include "core/subdiv/scheme.h"

namespace polarview::fuzz {

inline const char* const kSource = "fuzz.obj";

// What the target was doing, for the report of a finding.
inline std::string gStage;

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "\nFUZZ FINDING at [%s]: %s\n", gStage.c_str(), what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline bool allFinite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
inline void requireFinite(const Point& p, const std::string& what) {
  if (!allFinite(p))
    fail(what + " is not finite (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
         ")");
}
inline void requireFinite(double x, const std::string& what) {
  if (!std::isfinite(x)) fail(what + " is not finite (" + std::to_string(x) + ")");
}

// FNV-1a of the input's bytes: what a target picks from it (a level, a budget, a scheme) comes
// from the bytes alone, so a saved input reproduces its run.
inline uint32_t inputHash(const uint8_t* data, size_t size) {
  uint32_t hash = 2166136261u;
  for (size_t i = 0; i < size; ++i) hash = (hash ^ data[i]) * 16777619u;
  return hash;
}

// What a target takes: longer inputs, and meshes with more faces or vertices, are skipped (they
// are slow, not interesting: the targets look for wrong answers, not for the size limits).
struct InputLimits {
  size_t bytes;
  Index faces, vertices;
};

// The input as OBJ text through parseObjText. False for the reader's InputError (expected) and
// for input or meshes over `limits`.
inline bool parseInput(const uint8_t* data, size_t size, const InputLimits& limits, PolyMesh& mesh,
                       std::vector<std::string>* warnings = nullptr) {
  if (size > limits.bytes) return false;
  gStage = "parseObjText";
  try {
    mesh = parseObjText(std::string(reinterpret_cast<const char*>(data), size), kSource, warnings);
  } catch (const InputError&) {
    return false;
  }
  return mesh.faceCount() <= limits.faces && mesh.vertexCount() <= limits.vertices;
}

// One input of a target: polarview::InputError (bad input, a level over a budget) is expected,
// any other exception a finding.
template <class Body>
int runInput(Body&& body) {
  try {
    body();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    fail(std::string("unexpected exception: ") + e.what());
  } catch (...) {
    fail("unexpected non-std exception");
  }
  return 0;
}

inline uint64_t edgeKey(Index a, Index b) { return uint64_t(uint32_t(std::min(a, b))) << 32 | uint32_t(std::max(a, b)); }

// Whether face f names a vertex twice (the reader takes it: OpenSubdiv's degenerate edge).
inline bool repeatsVertex(const PolyMesh& mesh, Index f) {
  std::vector<Index> loop(mesh.face(f), mesh.face(f) + mesh.faceSize(f));
  std::sort(loop.begin(), loop.end());
  return std::adjacent_find(loop.begin(), loop.end()) != loop.end();
}

// Faces well formed: offsets from 0 to the corner count, at least 3 corners, vertex ids in range.
// [O(corners)]
inline void checkFaces(const PolyMesh& mesh, const std::string& whose) {
  if (mesh.faceStart.empty() || mesh.faceStart[0] != 0 || size_t(mesh.faceStart.back()) != mesh.faceVerts.size())
    fail(whose + ": face offsets do not run from 0 to the corner count");
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    const Index k = mesh.faceStart[f + 1] - mesh.faceStart[f];
    if (k < 3) fail(whose + ": face " + std::to_string(f) + " has " + std::to_string(k) + " corners");
    for (Index c = 0; c < k; ++c)
      if (mesh.face(f)[c] < 0 || mesh.face(f)[c] >= mesh.vertexCount())
        fail(whose + ": face " + std::to_string(f) + " has vertex id " + std::to_string(mesh.face(f)[c]) + " (" +
             std::to_string(mesh.vertexCount()) + " vertices)");
  }
}

// Tags as PolyMesh documents them: creases (v0 < v1) sorted by edge, each once, on an edge of some
// face; corners sorted, each once; sharpness finite and > 0; holes sorted face ids, each once.
// [O(corners log)]
inline void checkTags(const PolyMesh& mesh, const std::string& whose) {
  const SubdivTags& tags = mesh.tags;
  const Index vertices = mesh.vertexCount();
  // Messages are built for a finding only: the checks run on every input.
  auto sharpness = [&](double s, auto what) {
    if (!std::isfinite(s) || s <= 0.0) fail(whose + ": " + what() + " has sharpness " + std::to_string(s));
  };
  if (!tags.creases.empty()) {
    std::vector<uint64_t> edges;
    for (Index f = 0; f < mesh.faceCount(); ++f)
      for (Index c = 0; c < mesh.faceSize(f); ++c) edges.push_back(edgeKey(mesh.face(f)[c], mesh.face(f)[(c + 1) % mesh.faceSize(f)]));
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < tags.creases.size(); ++i) {
      const CreaseEdge& e = tags.creases[i];
      auto name = [&] { return "crease " + std::to_string(e.v0) + "-" + std::to_string(e.v1); };
      if (e.v0 < 0 || e.v0 >= e.v1 || e.v1 >= vertices) fail(whose + ": " + name() + " (" + std::to_string(vertices) + " vertices)");
      if (i > 0 && std::make_pair(tags.creases[i - 1].v0, tags.creases[i - 1].v1) >= std::make_pair(e.v0, e.v1))
        fail(whose + ": " + name() + " is not after the crease before it");
      if (!std::binary_search(edges.begin(), edges.end(), edgeKey(e.v0, e.v1))) fail(whose + ": " + name() + " is no edge of a face");
      sharpness(e.sharpness, name);
    }
  }
  for (size_t i = 0; i < tags.corners.size(); ++i) {
    const CornerVertex& c = tags.corners[i];
    auto name = [&] { return "corner " + std::to_string(c.vertex); };
    if (c.vertex < 0 || c.vertex >= vertices) fail(whose + ": " + name() + " (" + std::to_string(vertices) + " vertices)");
    if (i > 0 && tags.corners[i - 1].vertex >= c.vertex) fail(whose + ": " + name() + " is not after the corner before it");
    sharpness(c.sharpness, name);
  }
  for (size_t i = 0; i < tags.holes.size(); ++i) {
    const Index h = tags.holes[i];
    if (h < 0 || h >= mesh.faceCount()) fail(whose + ": hole face " + std::to_string(h) + " (" + std::to_string(mesh.faceCount()) + " faces)");
    if (i > 0 && tags.holes[i - 1] >= h) fail(whose + ": hole face " + std::to_string(h) + " is not after the hole before it");
  }
}

// What parseObjText guarantees of a mesh it returns (obj_io.h): at least one face, well-formed
// faces with their OBJ lines (increasing: one statement a face), every coordinate finite and at
// most kMaxObjCoordinate, valid tags. [O(corners log)]
inline void checkParsedMesh(const PolyMesh& mesh) {
  if (mesh.faceCount() < 1 || mesh.vertexCount() < 1)
    fail("parsed mesh with " + std::to_string(mesh.faceCount()) + " faces and " + std::to_string(mesh.vertexCount()) + " vertices");
  checkFaces(mesh, "parsed mesh");
  if (mesh.faceLine.size() != size_t(mesh.faceCount()))
    fail(std::to_string(mesh.faceLine.size()) + " face lines for " + std::to_string(mesh.faceCount()) + " faces");
  for (size_t f = 0; f < mesh.faceLine.size(); ++f)
    if (mesh.faceLine[f] < 1 || (f > 0 && mesh.faceLine[f] <= mesh.faceLine[f - 1]))
      fail("face " + std::to_string(f) + " on line " + std::to_string(mesh.faceLine[f]) + " (the face before it: line " +
           (f > 0 ? std::to_string(mesh.faceLine[f - 1]) : std::string("-")) + ")");
  for (size_t v = 0; v < mesh.points.size(); ++v) {
    const Point& p = mesh.points[v];
    if (!allFinite(p)) requireFinite(p, "parsed point " + std::to_string(v));
    const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    if (m > kMaxObjCoordinate) fail("parsed point " + std::to_string(v) + " has a coordinate of magnitude " + std::to_string(m));
  }
  checkTags(mesh, "parsed mesh");
}

// Polar configurations as polar_config.h describes them, refinable or not: exactly the candidates
// (used, interior vertices of valence >= 3 whose faces are all triangles), each once and in vertex
// order; `links` holds linkCount rings of `valence` ids in range; a rejected one says why. A
// refinable one: valence >= 3, >= 2 links, its fan triangles (pole, q_1j, q_1,j+1) as the faces
// wind, its ids distinct, each link a ring of edges joined to the next one by edges, no crease or
// corner on any link (a tag beyond link 3 cuts the links short), no hole at links 0..3, its
// stencil (pole and 1-link) apart from the other refinable poles'; schemeRefinesPole agrees with
// the schemes' minimum valences. [O(mesh)]
inline void checkPolarConfigs(const PolyMesh& mesh, const MeshTopology& topo, const std::vector<PolarConfig>& configs) {
  const Index vertices = mesh.vertexCount();
  auto inRange = [&](Index v) { return v >= 0 && v < vertices; };
  auto candidate = [&](Index v) {
    if (!topo.vertexUsed[size_t(v)] || topo.vertexOnBoundary[size_t(v)] || topo.valence(v) < 3) return false;
    for (Index k = topo.vertexFaceStart[size_t(v)]; k < topo.vertexFaceStart[size_t(v) + 1]; ++k)
      if (mesh.faceSize(topo.vertexFaces[size_t(k)]) != 3) return false;
    return true;
  };
  size_t next = 0;  // configs are the candidates in vertex order
  for (Index v = 0; v < vertices; ++v) {
    if (!candidate(v)) continue;
    if (next >= configs.size() || configs[next].pole != v)
      fail("candidate pole " + std::to_string(v) + " has no polar configuration (or not in vertex order)");
    ++next;
  }
  if (next != configs.size()) fail(std::to_string(configs.size()) + " polar configurations for " + std::to_string(next) + " candidates");

  std::vector<uint8_t> sharp(size_t(vertices), 0), stencil(size_t(vertices), 0);
  for (const CreaseEdge& c : mesh.tags.creases) sharp[size_t(c.v0)] = sharp[size_t(c.v1)] = 1;
  for (const CornerVertex& c : mesh.tags.corners) sharp[size_t(c.vertex)] = 1;
  const std::vector<uint8_t> holes = baseHoles(mesh, topo);
  std::vector<Index> ids;
  for (const PolarConfig& c : configs) {
    auto pole = [&] { return "pole " + std::to_string(c.pole); };
    if (c.valence != topo.valence(c.pole)) fail(pole() + " has valence " + std::to_string(c.valence) + ", the mesh " + std::to_string(topo.valence(c.pole)));
    if (c.linkCount < 0 || c.links.size() != size_t(c.linkCount) * size_t(c.valence))
      fail(pole() + ": " + std::to_string(c.links.size()) + " link ids for " + std::to_string(c.linkCount) + " links of valence " +
           std::to_string(c.valence));
    for (Index q : c.links)
      if (!inRange(q)) fail(pole() + ": link vertex " + std::to_string(q));
    if (c.refinable != (c.rejection == PolarRejection::None) || c.refinable != c.reason.empty())
      fail(pole() + ": refinable " + std::to_string(c.refinable) + " with rejection '" + polarRejectionKey(c.rejection) + "' and reason '" +
           c.reason + "'");
    if ((c.outer == PolarConfig::Outer::Pole) != (c.oppositePole >= 0) ||
        (c.oppositePole >= 0 && (!inRange(c.oppositePole) || c.oppositePole == c.pole)))
      fail(pole() + ": opposite pole " + std::to_string(c.oppositePole));
    for (const Scheme s : {Scheme::CatmullClark, Scheme::C2PS, Scheme::RTS, Scheme::BPS}) {
      const SchemeTraits& traits = schemeTraits(s);
      const bool expected = traits.polar() && c.refinable && c.valence >= traits.minValence;
      if (schemeRefinesPole(s, c) != expected) fail(pole() + ": schemeRefinesPole(" + traits.name + ") is " + std::to_string(!expected));
    }
    if (!c.refinable) continue;

    const int n = c.valence;
    if (n < 3) fail("refinable " + pole() + " of valence " + std::to_string(n));
    if (c.linkCount < 2) fail("refinable " + pole() + " with " + std::to_string(c.linkCount) + " links");
    if (c.regularLinks < 1 || c.regularLinks > c.linkCount)
      fail("refinable " + pole() + " with " + std::to_string(c.regularLinks) + " regular links of " + std::to_string(c.linkCount));
    ids.assign(c.links.begin(), c.links.end());
    ids.push_back(c.pole);
    std::sort(ids.begin(), ids.end());
    if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) fail("refinable " + pole() + " names a vertex twice");
    // Fan triangles (pole, q_1j, q_1,j+1) in the faces' winding.
    for (int j = 0; j < n; ++j) {
      const Index a = c.links[size_t(j)], b = c.links[size_t((j + 1) % n)];
      bool found = false;
      for (Index k = topo.vertexFaceStart[size_t(c.pole)]; k < topo.vertexFaceStart[size_t(c.pole) + 1] && !found; ++k) {
        const Index* t = mesh.face(topo.vertexFaces[size_t(k)]);
        for (int r = 0; r < 3; ++r) found = found || (t[r] == c.pole && t[(r + 1) % 3] == a && t[(r + 2) % 3] == b);
      }
      if (!found) fail("refinable " + pole() + ": no fan triangle (pole, " + std::to_string(a) + ", " + std::to_string(b) + ")");
    }
    // Each link a ring of edges, joined to the next link by edges.
    for (int i = 0; i < c.linkCount; ++i)
      for (int j = 0; j < n; ++j) {
        const Index q = c.links[size_t(i * n + j)];
        if (topo.edgeBetween(q, c.links[size_t(i * n + (j + 1) % n)]) < 0)
          fail("refinable " + pole() + ": link " + std::to_string(i + 1) + " is no ring of edges at " + std::to_string(q));
        if (i + 1 < c.linkCount && topo.edgeBetween(q, c.links[size_t((i + 1) * n + j)]) < 0)
          fail("refinable " + pole() + ": no edge from link " + std::to_string(i + 1) + " to the next at " + std::to_string(q));
      }
    for (int k = -1; k < c.linkCount * n; ++k) {
      const Index q = k < 0 ? c.pole : c.links[size_t(k)];
      if (sharp[size_t(q)]) fail("refinable " + pole() + " has a crease or corner at vertex " + std::to_string(q));
      if (holes.empty() || k >= 3 * n) continue;
      for (Index f = topo.vertexFaceStart[size_t(q)]; f < topo.vertexFaceStart[size_t(q) + 1]; ++f)
        if (holes[size_t(topo.vertexFaces[size_t(f)])]) fail("refinable " + pole() + " has a hole at vertex " + std::to_string(q));
    }
    for (int k = -1; k < n; ++k) {
      const Index q = k < 0 ? c.pole : c.links[size_t(k)];
      if (stencil[size_t(q)]) fail("refinable " + pole() + "'s stencil overlaps another refinable pole's at vertex " + std::to_string(q));
      stencil[size_t(q)] = 1;
    }
  }
}

}  // namespace polarview::fuzz
