// OBJ reading and writing with strict validation: every error names FILE:LINE.
// tinyobjloader is not used for reading because it cannot report the file line of an error (it
// silently skips or clamps bad statements), and polarview must say exactly which line is wrong.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "core/mesh/input_error.h"
#include "core/mesh/poly_mesh.h"

namespace polarview {

// Reads an OBJ file: `v` and `f` statements (texture/normal parts of `f a/b/c` ignored; negative
// indices resolved relative to the vertices read so far). Fills PolyMesh::faceLine. Throws
// InputError(path, line, msg) for unreadable, empty, binary or malformed input, non-finite
// coordinates, bad indices, faces with < 3 vertices or a repeated vertex. Non-fatal findings
// (unreferenced vertices, ignored `l`/`p`/`t` statements) go to `warnings`. [O(file size)]
PolyMesh loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Same as loadObj on an already opened stream; `sourceName` is the file name used in errors.
PolyMesh parseObj(std::istream& in, const std::string& sourceName, std::vector<std::string>* warnings = nullptr);

// Same as parseObj on text already in memory. [O(text size)]
PolyMesh parseObjText(const std::string& text, const std::string& sourceName,
                      std::vector<std::string>* warnings = nullptr);

// Writes `v` lines with 17 significant digits (doubles round-trip exactly) and 1-based `f` lines.
// Writes path + ".tmp" then renames it, so a failure never leaves a partial file at `path`.
// Throws InputError(path, 0, msg) on failure. [O(mesh)]
void saveObj(const std::string& path, const PolyMesh& mesh);

}  // namespace polarview
