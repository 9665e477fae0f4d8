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

// The largest coordinate magnitude the reader accepts. Squares of coordinates and sums of
// thousands of them (lengths, dot products, the schemes' weighted sums) then stay finite, so no
// result holds inf or NaN.
constexpr double kMaxObjCoordinate = 1e150;

// Reads an OBJ file: `v` and `f` statements (texture/normal parts of `f a/b/c` ignored; negative
// indices resolved relative to the vertices read so far). Lines end at LF, CRLF or a lone CR; a
// leading UTF-8 byte-order mark is skipped. Fills PolyMesh::faceLine. Throws
// InputError(path, line, msg) for unreadable, empty, binary or malformed input, non-finite
// coordinates or ones over kMaxObjCoordinate, bad indices, faces with < 3 vertices or a repeated
// vertex. Non-fatal findings (unreferenced vertices, ignored `l`/`p`/`t` statements) go to
// `warnings`. [O(file size)]
PolyMesh loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Same as loadObj on an already opened stream; `sourceName` is the file name used in errors.
PolyMesh parseObj(std::istream& in, const std::string& sourceName, std::vector<std::string>* warnings = nullptr);

// Same as parseObj on text already in memory. [O(text size)]
PolyMesh parseObjText(const std::string& text, const std::string& sourceName,
                      std::vector<std::string>* warnings = nullptr);

// Writes `v` lines with 17 significant digits (doubles round-trip exactly) and 1-based `f` lines,
// atomically (atomic_file.h): a failure or a kill never leaves a partial file or a temporary.
// A non-finite coordinate is refused before anything is written: InputError naming `sourceName`
// (the input the mesh came from; `path` when empty). Other failures: InputError(path, 0, msg).
// [O(mesh)]
void saveObj(const std::string& path, const PolyMesh& mesh, const std::string& sourceName = "");

}  // namespace polarview
