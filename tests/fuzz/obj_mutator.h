// The structure-aware mutator of every fuzz target here (README.md): half of libFuzzer's mutations
// stay its own byte-level ones, half edit the OBJ as a mesh. Defines LLVMFuzzerCustomMutator:
// include it in exactly one translation unit of a target.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace polarview::fuzz {

// Half of the mutations edit the OBJ as a mesh (libFuzzer's byte-level ones rarely keep it valid):
// move a coordinate (scaled, zeroed, copied, made nearly equal), retarget a face index, flip a
// face, delete or duplicate a line, split a polygon into a triangle fan, poke a face (a new
// triangle fan around its centre: a new polar candidate of the face's valence), merge two
// vertices, start a face at another corner, or add a crease, corner or hole tag on a face. Face
// indices written are 1-based and positive, tag ids 0-based (OpenSubdiv's).

struct ObjLines {
  std::vector<std::string> lines;
  std::vector<size_t> vertexLines, faceLines;
};

inline ObjLines splitObj(const uint8_t* data, size_t size) {
  ObjLines obj;
  std::string line;
  for (size_t i = 0; i <= size; ++i) {
    if (i == size || data[i] == '\n') {
      if (line.rfind("v ", 0) == 0) obj.vertexLines.push_back(obj.lines.size());
      if (line.rfind("f ", 0) == 0) obj.faceLines.push_back(obj.lines.size());
      obj.lines.push_back(line);
      line.clear();
    } else {
      line += char(data[i]);
    }
  }
  return obj;
}

inline std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

// The vertex part of a face corner ("12/3/4" -> 12), made positive against `vertexCount`.
inline long cornerIndex(const std::string& corner, long vertexCount) {
  const long i = std::strtol(corner.c_str(), nullptr, 10);
  return i < 0 ? vertexCount + 1 + i : i;
}

inline std::string joinFace(const std::vector<long>& loop) {
  std::string line = "f";
  for (long i : loop) line += " " + std::to_string(i);
  return line;
}

inline std::vector<long> faceLoop(const std::string& line, long vertexCount) {
  std::vector<std::string> t = tokens(line);
  std::vector<long> loop;
  for (size_t k = 1; k < t.size(); ++k) loop.push_back(cornerIndex(t[k], vertexCount));
  return loop;
}

inline bool mutateObj(ObjLines& obj, std::minstd_rand& rng) {
  auto pick = [&](size_t n) { return size_t(rng() % n); };
  const long vertexCount = long(obj.vertexLines.size());
  std::vector<std::string>& lines = obj.lines;
  switch (rng() % 10) {
    case 0: {  // move one coordinate
      if (obj.vertexLines.empty()) return false;
      const size_t v = obj.vertexLines[pick(obj.vertexLines.size())];
      std::vector<std::string> t = tokens(lines[v]);
      if (t.size() < 4) return false;
      const size_t c = 1 + pick(3);
      const double x = std::strtod(t[c].c_str(), nullptr);
      const double other =
          std::strtod(tokens(lines[obj.vertexLines[pick(obj.vertexLines.size())]]).back().c_str(), nullptr);
      const double choices[] = {0.0,     -x,       2.0 * x, x * (1.0 + 1e-12),         x + 1e-9,
                                x * 1e6, x * 1e-6, other,   double(int(rng() % 7) - 3)};
      char buffer[40];
      std::snprintf(buffer, sizeof buffer, "%.17g", choices[pick(9)]);
      t[c] = buffer;
      std::string line = t[0];
      for (size_t k = 1; k < t.size(); ++k) line += " " + t[k];
      lines[v] = line;
      return true;
    }
    case 1: {  // retarget one index of a face
      if (obj.faceLines.empty() || vertexCount == 0) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.empty()) return false;
      loop[pick(loop.size())] = 1 + long(pick(size_t(vertexCount)));
      lines[f] = joinFace(loop);
      return true;
    }
    case 2: {  // flip a face
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      std::reverse(loop.begin(), loop.end());
      lines[f] = joinFace(loop);
      return true;
    }
    case 3: {  // delete a face or a vertex line
      const std::vector<size_t>& from = rng() % 4 ? obj.faceLines : obj.vertexLines;
      if (from.empty()) return false;
      lines.erase(lines.begin() + long(from[pick(from.size())]));
      return true;
    }
    case 4: {  // duplicate a face
      if (obj.faceLines.empty()) return false;
      const std::string line = lines[obj.faceLines[pick(obj.faceLines.size())]];
      lines.push_back(line);
      return true;
    }
    case 5: {  // split a polygon into a fan of triangles from one corner
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.size() < 4) return false;
      std::rotate(loop.begin(), loop.begin() + long(pick(loop.size())), loop.end());
      lines[f] = joinFace({loop[0], loop[1], loop[2]});
      for (size_t k = 2; k + 1 < loop.size(); ++k) lines.push_back(joinFace({loop[0], loop[k], loop[k + 1]}));
      return true;
    }
    case 6: {  // poke a face: a vertex at its centre (lifted a little) and a triangle fan around it
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.size() < 3) return false;
      double centre[3] = {0, 0, 0};
      for (long i : loop) {
        if (i < 1 || i > vertexCount) return false;
        std::vector<std::string> t = tokens(lines[obj.vertexLines[size_t(i - 1)]]);
        for (size_t c = 0; c < 3 && c + 1 < t.size(); ++c)
          centre[c] += std::strtod(t[c + 1].c_str(), nullptr) / double(loop.size());
      }
      char buffer[120];
      std::snprintf(buffer, sizeof buffer, "v %.17g %.17g %.17g", centre[0], centre[1],
                    centre[2] + 0.01 * double(rng() % 3));
      lines.insert(lines.begin() + long(obj.vertexLines.back()) + 1, buffer);  // keeps earlier faces' indices
      const long pole = vertexCount + 1;
      lines[f + (f > obj.vertexLines.back() ? 1 : 0)] = joinFace({pole, loop[0], loop[1]});
      for (size_t k = 1; k < loop.size(); ++k) lines.push_back(joinFace({pole, loop[k], loop[(k + 1) % loop.size()]}));
      return true;
    }
    case 7: {  // merge vertex a into b in every face
      if (vertexCount < 2 || obj.faceLines.empty()) return false;
      const long a = 1 + long(pick(size_t(vertexCount))), b = 1 + long(pick(size_t(vertexCount)));
      for (size_t f : obj.faceLines) {
        std::vector<long> loop = faceLoop(lines[f], vertexCount);
        std::vector<long> merged;
        for (long i : loop)
          if ((i == a ? b : i) != (merged.empty() ? 0 : merged.back())) merged.push_back(i == a ? b : i);
        if (merged.size() > 1 && merged.front() == merged.back()) merged.pop_back();
        lines[f] = merged.size() >= 3 ? joinFace(merged) : "";
      }
      return true;
    }
    case 8: {  // tag an edge, a corner or a face of a face (OpenSubdiv's `t` tags: ids 0-based)
      if (obj.faceLines.empty()) return false;
      std::vector<long> loop = faceLoop(lines[obj.faceLines[pick(obj.faceLines.size())]], vertexCount);
      if (loop.size() < 2) return false;
      const size_t k = pick(loop.size());
      const char* const sharpness[] = {"1", "2.5", "10", "0", "0.25"};
      const char* s = sharpness[pick(5)];
      switch (rng() % 3) {
        case 0:
          lines.push_back("t crease 2/1/0 " + std::to_string(loop[k] - 1) + " " + std::to_string(loop[(k + 1) % loop.size()] - 1) + " " + s);
          break;
        case 1: lines.push_back("t corner 1/1/0 " + std::to_string(loop[k] - 1) + " " + s); break;
        default: lines.push_back("t hole 1/0/0 " + std::to_string(pick(obj.faceLines.size()))); break;
      }
      return true;
    }
    default: {  // start a face at its next corner (the same face: nothing may change but numbering)
      if (obj.faceLines.empty()) return false;
      const size_t f = obj.faceLines[pick(obj.faceLines.size())];
      std::vector<long> loop = faceLoop(lines[f], vertexCount);
      if (loop.empty()) return false;
      std::rotate(loop.begin(), loop.begin() + 1, loop.end());
      lines[f] = joinFace(loop);
      return true;
    }
  }
}

}  // namespace polarview::fuzz

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

// Half libFuzzer's own byte-level mutations, half mesh edits (mutateObj above).
extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t maxSize, unsigned int seed) {
  std::minstd_rand rng(seed);
  if (rng() % 2 == 0) return LLVMFuzzerMutate(data, size, maxSize);
  using namespace polarview::fuzz;
  ObjLines obj = splitObj(data, size);
  if (!mutateObj(obj, rng)) return LLVMFuzzerMutate(data, size, maxSize);
  std::string text;
  for (size_t k = 0; k < obj.lines.size(); ++k) text += obj.lines[k] + (k + 1 < obj.lines.size() ? "\n" : "");
  if (text.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
  std::copy(text.begin(), text.end(), data);
  return text.size();
}
