// OBJ reading and writing with strict validation: every error names FILE:LINE.
// The reader is polarview's own, not tinyobjloader: tinyobjloader loses data on valid files (face
// sizes over 255, tags, the last bits of doubles) and reports no lines; docs/toolchain.md.
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
// indices resolved relative to the vertices read so far) and OpenSubdiv's `t` tags (crease,
// corner, hole, interpolateboundary, creasemethod, smoothtriangles -> PolyMesh::tags). Lines end
// at LF, CRLF or a lone CR; a leading UTF-8 byte-order mark is skipped. Fills PolyMesh::faceLine.
// The file is read in 64 KiB chunks and checked as it comes: binary data or an unknown statement
// is refused at its chunk, before the rest is read. Throws InputError(path, line, msg) for
// unreadable, empty, binary or malformed input, non-finite coordinates or ones over
// kMaxObjCoordinate, bad indices, faces with < 3 vertices, malformed tags, tag ids out of range,
// negative or non-finite sharpness, crease edges that are no edge. A face repeating a vertex is
// read (OpenSubdiv's degenerate edge; manifold_split.h decides what refines). Non-fatal
// findings (unreferenced vertices, ignored `l`/`p` statements and tags) go to `warnings`.
// [O(file size), memory O(mesh + longest line)]
// With `text`, the bytes read are kept there as read (byte-order mark and line ends included): the
// source saveObjEdited writes an edited mesh into, without reading the file again (which may have
// changed on disk since). [memory then also O(file size)]
PolyMesh loadObj(const std::string& path, std::vector<std::string>* warnings = nullptr, std::string* text = nullptr);

// Same as loadObj on an already opened stream; `sourceName` is the file name used in errors.
PolyMesh parseObj(std::istream& in, const std::string& sourceName, std::vector<std::string>* warnings = nullptr);

// Same as parseObj on text already in memory. [O(text size)]
PolyMesh parseObjText(const std::string& text, const std::string& sourceName,
                      std::vector<std::string>* warnings = nullptr);

// Writes `v` lines, 1-based `f` lines and `t` lines for mesh.tags (options only where not the
// default) to `out`. Each number is the shortest decimal that reads back to the same double
// (std::to_chars' shortest form: 0.19509 stays "0.19509"). [O(mesh)]
void writeObj(std::ostream& out, const PolyMesh& mesh);
// writeObj into `path`, atomically (atomic_file.h): a failure or a kill never leaves a partial file
// or a temporary. A non-finite coordinate or sharpness is refused before anything is written:
// InputError naming `sourceName` (the input the mesh came from; `path` when empty). Other failures:
// InputError(path, 0, msg). [O(mesh)]
void saveObj(const std::string& path, const PolyMesh& mesh, const std::string& sourceName = "");

// Writes `mesh` into `sourceText`, the OBJ text it was read from (loadObj's `text`) before its
// points were edited: every byte of the source as it is (comments, groups, materials, vt/vn lines,
// face index triples `f 1/2/3`, `t` tags, line ends, order) except, on the `v` statements of
// vertices that moved, the coordinates that changed, written shortest as saveObj writes them (the
// rest of such a line, w or colour fields and a comment included, stays). A `v` statement
// continued over lines with backslashes becomes one line when it changes. Where `mesh` is not the
// source's (another vertex count, other faces or tags, e.g. a conversion's result) there is nothing
// to keep: writes as saveObj and returns false. Atomic and refusing non-finite coordinates as
// saveObj. [O(source size + mesh)]
bool saveObjEdited(const std::string& path, const PolyMesh& mesh, const std::string& sourceText,
                   const std::string& sourceName = "");

}  // namespace polarview
