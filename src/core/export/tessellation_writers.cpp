// PLY and glb writers of a Tessellation (tessellation_writers.h; docs/formats.md).
#include "core/export/tessellation_writers.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include <glm/geometric.hpp>

#include "core/mesh/input_error.h"

namespace polarview {

namespace {

// Little-endian bytes whatever the host's order.
void appendBits(std::string& out, uint64_t bits, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(char((bits >> (8 * k)) & 0xff));
}
void appendDouble(std::string& out, double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  appendBits(out, bits, 8);
}
void appendFloat(std::string& out, float x) {
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  appendBits(out, bits, 4);
}

// A name from the command line in a one-line header field: control characters become '?'.
std::string oneLine(const std::string& text) {
  std::string line = text;
  for (char& c : line)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  return line;
}

bool finite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

[[noreturn]] void refuseVertex(const Tessellation& mesh, const TessellationFileInfo& info, size_t v, const char* what) {
  const TessellationSource& s = mesh.sources[v];
  char where[160];
  std::snprintf(where, sizeof where, " at vertex %zu (patch %u, u = %.17g, v = %.17g)", v, s.patch, s.u, s.v);
  throw InputError(info.source, 0, std::string("the tessellation has ") + what + where +
                                       ": the input's coordinates are too large, too small or degenerate");
}

// Everything a file holds is finite and there is a colour per vertex (before any byte is made).
void checkWritable(const Tessellation& mesh, const TessellationFileInfo& info) {
  if (info.colours.size() != mesh.positions.size())
    throw InputError(info.source, 0, "tessellation: " + std::to_string(info.colours.size()) + " colours for " +
                                         std::to_string(mesh.positions.size()) + " vertices");
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!finite(mesh.positions[v])) refuseVertex(mesh, info, v, "a non-finite position");
    if (!finite(mesh.normals[v])) refuseVertex(mesh, info, v, "a non-finite normal");
    if (!std::isfinite(mesh.gaussian[v])) refuseVertex(mesh, info, v, "a non-finite Gaussian curvature");
    if (!std::isfinite(mesh.mean[v])) refuseVertex(mesh, info, v, "a non-finite mean curvature");
    const glm::vec3& c = info.colours[v];
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))) refuseVertex(mesh, info, v, "a non-finite colour");
  }
}

// glTF holds floats: a value past float's range is refused rather than written as infinity.
float toFloat(double x, const Tessellation& mesh, const TessellationFileInfo& info, size_t v, const char* what) {
  if (!(std::abs(x) <= double(std::numeric_limits<float>::max()))) refuseVertex(mesh, info, v, what);
  return float(x);
}

uint8_t colourByte(float c) { return uint8_t(std::lround(std::min(1.0f, std::max(0.0f, c)) * 255.0f)); }

// glTF's COLOR_0 is linear; the colour maps give sRGB (what the screen shows).
float srgbToLinear(float c) {
  c = std::min(1.0f, std::max(0.0f, c));
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

std::string jsonString(const std::string& text) {
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') quoted += '\\', quoted += c;
    else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", unsigned(static_cast<unsigned char>(c)));
      quoted += escape;
    } else quoted += c;
  }
  return quoted + '"';
}

// 9 significant digits: a float read back is the same float (the validator compares min/max).
std::string jsonFloat(float x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(x));
  return text;
}

// The glb's binary chunk: one tightly packed block per accessor, each a multiple of 4 bytes.
struct GlbBlocks {
  std::string bin;
  std::vector<std::pair<size_t, size_t>> views;  // byte offset, length
  size_t start = 0;
  // Ends the block begun at the previous close.
  void close() {
    views.push_back({start, bin.size() - start});
    start = bin.size();
  }
};

// The JSON chunk: accessors 0..5 = POSITION, NORMAL, COLOR_0, _GAUSSIAN_CURVATURE, _MEAN_CURVATURE,
// indices, each on its own buffer view.
std::string glbJson(const Tessellation& mesh, const TessellationFileInfo& info, const GlbBlocks& blocks,
                    const glm::vec3& low, const glm::vec3& high) {
  const size_t vertices = mesh.positions.size(), indices = 3 * mesh.triangles.size();
  std::string json = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"polarview\",\"extras\":{\"source\":" +
                     jsonString(info.source) + ",\"scheme\":" + jsonString(info.schemeLabel) +
                     ",\"level\":" + std::to_string(info.level) + ",\"samples\":" + std::to_string(mesh.samples) +
                     ",\"colouring\":" + jsonString(info.colouring) + "}},";
  json += "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"limit surface\"}],";
  json += "\"materials\":[{\"name\":\"curvature colours\",\"pbrMetallicRoughness\":{\"metallicFactor\":0,"
          "\"roughnessFactor\":0.7}}],";
  json += "\"meshes\":[{\"name\":\"limit surface\",\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
          "\"COLOR_0\":2,\"_GAUSSIAN_CURVATURE\":3,\"_MEAN_CURVATURE\":4},\"indices\":5,\"mode\":4,\"material\":0}]}],";
  json += "\"buffers\":[{\"byteLength\":" + std::to_string(blocks.bin.size()) + "}],\"bufferViews\":[";
  for (size_t k = 0; k < blocks.views.size(); ++k)
    json += std::string(k ? "," : "") + "{\"buffer\":0,\"byteOffset\":" + std::to_string(blocks.views[k].first) +
            ",\"byteLength\":" + std::to_string(blocks.views[k].second) + ",\"target\":" + (k == 5 ? "34963" : "34962") + "}";
  const auto accessor = [&](int view, int componentType, size_t count, const char* type) {
    return "{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" + std::to_string(componentType) +
           ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"";
  };
  json += "],\"accessors\":[" + accessor(0, 5126, vertices, "VEC3") + ",\"min\":[" + jsonFloat(low.x) + "," +
          jsonFloat(low.y) + "," + jsonFloat(low.z) + "],\"max\":[" + jsonFloat(high.x) + "," + jsonFloat(high.y) +
          "," + jsonFloat(high.z) + "]},";
  json += accessor(1, 5126, vertices, "VEC3") + "}," + accessor(2, 5126, vertices, "VEC3") + "}," +
          accessor(3, 5126, vertices, "SCALAR") + "}," + accessor(4, 5126, vertices, "SCALAR") + "}," +
          accessor(5, 5125, indices, "SCALAR") + "}]}";
  return json;
}

void appendChunk(std::string& out, std::string chunk, uint32_t type, char padding) {
  while (chunk.size() % 4) chunk.push_back(padding);
  appendBits(out, chunk.size(), 4);
  appendBits(out, type, 4);
  out += chunk;
}

}  // namespace

std::string plyBytes(const Tessellation& mesh, const TessellationFileInfo& info) {
  checkWritable(mesh, info);
  if (mesh.positions.size() > size_t(std::numeric_limits<int32_t>::max()))
    throw InputError(info.source, 0, "tessellation: more vertices than PLY's int indices hold");
  std::string out = "ply\nformat binary_little_endian 1.0\n";
  out += "comment polarview tessellation of " + oneLine(info.source) + ": " + oneLine(info.schemeLabel) + " level " +
         std::to_string(info.level) + ", " + std::to_string(mesh.samples) + " segments per patch edge\n";
  out += "comment exact at every vertex: position, normal, K, H of the limit surface (docs/formats.md)\n";
  out += "comment quality = gaussian_curvature; colours: " + oneLine(info.colouring) + "\n";
  out += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "quality", "gaussian_curvature", "mean_curvature"})
    out += std::string("property double ") + name + "\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "element face " + std::to_string(mesh.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + mesh.positions.size() * 75 + mesh.triangles.size() * 13);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    for (int k = 0; k < 3; ++k) appendDouble(out, mesh.positions[v][k]);
    for (int k = 0; k < 3; ++k) appendDouble(out, mesh.normals[v][k]);
    appendDouble(out, mesh.gaussian[v]);
    appendDouble(out, mesh.gaussian[v]);
    appendDouble(out, mesh.mean[v]);
    for (int k = 0; k < 3; ++k) out.push_back(char(colourByte(info.colours[v][k])));
  }
  for (const auto& triangle : mesh.triangles) {
    out.push_back(char(3));
    for (uint32_t index : triangle) appendBits(out, index, 4);
  }
  return out;
}

std::string glbBytes(const Tessellation& mesh, const TessellationFileInfo& info) {
  checkWritable(mesh, info);
  const size_t vertices = mesh.positions.size();
  GlbBlocks blocks;
  blocks.bin.reserve(vertices * 44 + mesh.triangles.size() * 12);

  // Positions (and their float bounds), normals, colours, K, H, indices.
  glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
  for (size_t v = 0; v < vertices; ++v)
    for (int k = 0; k < 3; ++k) {
      const float x = toFloat(mesh.positions[v][k], mesh, info, v, "a position past float's range");
      low[k] = std::min(low[k], x), high[k] = std::max(high[k], x);
      appendFloat(blocks.bin, x);
    }
  blocks.close();
  for (size_t v = 0; v < vertices; ++v) {
    const glm::vec3 n = glm::normalize(glm::vec3(mesh.normals[v]));
    for (int k = 0; k < 3; ++k) appendFloat(blocks.bin, n[k]);
  }
  blocks.close();
  for (size_t v = 0; v < vertices; ++v)
    for (int k = 0; k < 3; ++k) appendFloat(blocks.bin, srgbToLinear(info.colours[v][k]));
  blocks.close();
  for (size_t v = 0; v < vertices; ++v) appendFloat(blocks.bin, toFloat(mesh.gaussian[v], mesh, info, v, "a K past float's range"));
  blocks.close();
  for (size_t v = 0; v < vertices; ++v) appendFloat(blocks.bin, toFloat(mesh.mean[v], mesh, info, v, "an H past float's range"));
  blocks.close();
  for (const auto& triangle : mesh.triangles)
    for (uint32_t index : triangle) appendBits(blocks.bin, index, 4);
  blocks.close();

  // Header (magic "glTF", version 2, total length), JSON chunk (space-padded), BIN chunk.
  std::string chunks;
  appendChunk(chunks, glbJson(mesh, info, blocks, low, high), 0x4E4F534Au, ' ');
  appendChunk(chunks, std::move(blocks.bin), 0x004E4942u, '\0');
  if (chunks.size() > size_t(std::numeric_limits<uint32_t>::max()) - 12)
    throw InputError(info.source, 0, "tessellation: over 4 GiB, more than a glb file holds");
  std::string out;
  appendBits(out, 0x46546C67u, 4);
  appendBits(out, 2, 4);
  appendBits(out, 12 + chunks.size(), 4);
  return out + chunks;
}

}  // namespace polarview
