// Strict streaming OBJ reader and atomic OBJ writer (see obj_io.h).
#include "core/mesh/obj_io.h"

#include "core/mesh/atomic_file.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <ostream>
#include <iterator>
#include <memory>
#include <string_view>

namespace polarview {

namespace {

// [SECTION] Lexical helpers

// How much of the file is read at a time: the most the reader holds besides the mesh and one line.
constexpr size_t kReadChunk = size_t(1) << 16;

bool isBlank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v'; }

// Bytes that never occur in a text OBJ file: control characters other than whitespace, and DEL.
bool isBinaryByte(unsigned char ch) {
  if (ch == '\n' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v') return false;
  return ch < 0x20 || ch == 0x7f;
}

// Statements of the OBJ format polarview does not need (free-form geometry, grouping, materials,
// rendering attributes): skipped without a word. Anything else that is not v/f/l/p/t is an error.
constexpr std::string_view kIgnoredStatements[] = {
    "vt", "vn", "vp", "g", "o", "s", "mg", "usemtl", "mtllib", "maplib", "usemap", "lod", "bevel",
    "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech", "stech", "cstype", "deg", "bmat",
    "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con"};
constexpr std::string_view kReadStatements[] = {"v", "f", "fo", "l", "p", "t"};
constexpr size_t kLongestKeyword = 10;  // "shadow_obj", "trace_obj"

bool isKnownStatement(std::string_view keyword) {
  auto in = [&](const auto& list) { return std::find(std::begin(list), std::end(list), keyword) != std::end(list); };
  return in(kReadStatements) || in(kIgnoredStatements);
}

// Whether a line ends (before trailing blanks and a CR) with a continuation backslash.
bool continues(std::string_view line) {
  size_t end = line.find_last_not_of(" \t\r");
  return end != std::string_view::npos && line[end] == '\\';
}
// The line up to its continuation backslash.
std::string_view withoutContinuation(std::string_view line) { return line.substr(0, line.find_last_of('\\')); }
// The line before its comment (comments run to the end of the line).
std::string_view withoutComment(std::string_view line) { return line.substr(0, line.find('#')); }

// Splits one line into whitespace-separated tokens without allocating.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : rest_(line) {}
  // Next token, or an empty view at the end of the line.
  std::string_view next() {
    size_t i = 0;
    while (i < rest_.size() && isBlank(rest_[i])) ++i;
    size_t j = i;
    while (j < rest_.size() && !isBlank(rest_[j])) ++j;
    std::string_view token = rest_.substr(i, j - i);
    rest_.remove_prefix(j);
    return token;
  }
  // Whether the line has nothing but blanks left.
  bool atEnd() const { return std::all_of(rest_.begin(), rest_.end(), isBlank); }

 private:
  std::string_view rest_;
};

std::string quoted(std::string_view token) {
  constexpr size_t kMaxShown = 24;  // keep one-line messages short on garbage input
  std::string s(token.substr(0, kMaxShown));
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) >= 0x7f) ch = '?';
  return "'" + s + (token.size() > kMaxShown ? "...'" : "'");
}

// A checked number as written, cut short when it is very long.
std::string shortened(std::string_view number) {
  constexpr size_t kMaxShown = 24;
  return number.size() <= kMaxShown ? std::string(number) : std::string(number.substr(0, kMaxShown)) + "...";
}

// A decimal integer with an optional '-': its sign and magnitude, the magnitude saturated just
// past `limit` (no overflow, no negation of an extreme value, whatever the digits). False when
// the token is not such a number.
bool parseDecimal(std::string_view token, uint64_t limit, bool* negative, uint64_t* magnitude) {
  *negative = !token.empty() && token.front() == '-';
  std::string_view digits = token.substr(*negative ? 1 : 0);
  if (digits.empty()) return false;
  *magnitude = 0;
  for (char ch : digits) {
    if (ch < '0' || ch > '9') return false;
    if (*magnitude <= limit) *magnitude = *magnitude * 10 + uint64_t(ch - '0');
  }
  return true;
}

uint64_t edgeKey(Index a, Index b) { return uint64_t(uint32_t(std::min(a, b))) << 32 | uint32_t(std::max(a, b)); }

// [SECTION] The reader

// Reads OBJ text as it arrives (feed), so a hostile file is refused at its first bad chunk, not
// after it has been read whole: lines are cut at LF, CRLF or a lone CR across chunk ends, and
// statements are parsed and checked one by one. What needs the whole file (indices that point
// forward, tag ids) is checked in finish().
//
// Why not tinyobjloader (Debian's 2.0.0rc10, which the design names): it cannot keep this reader's
// guarantees, also on valid files. Its numbers are not correctly rounded (saved doubles would not
// read back bit for bit), LoadObj stores face sizes in a byte (a 300-gon becomes a 44-gon), keeps
// tags only with a group that has faces and caps a tag at 8192 values, its callback API drops
// tags, errors have no line, and it reads a line whole (a file of NUL bytes is one line). Checking
// every line first and then handing it over would still lose such data; see docs/toolchain.md.
class ObjParser {
 public:
  ObjParser(const std::string& sourceName, std::vector<std::string>* warnings)
      : source_(sourceName), warnings_(warnings) {}

  // The next bytes of the file: complete lines are parsed at once, the unfinished last one kept.
  // A byte that never occurs in text fails here, naming its line. [O(bytes)]
  void feed(std::string_view bytes) {
    if (!headDone_) {
      // A UTF-8 byte-order mark (Windows editors write one) is not part of the first statement;
      // it may arrive split over the first reads.
      const size_t take = std::min(kUtf8Bom.size() - head_.size(), bytes.size());
      head_.append(bytes.substr(0, take));
      bytes.remove_prefix(take);
      if (head_.size() < kUtf8Bom.size()) return;
      flushHead();
    }
    consume(bytes);
  }

  // The end of the file: parses the last line, checks indices and tags, returns the mesh.
  PolyMesh finish() {
    if (!headDone_) flushHead();
    if (!pending_.empty()) {
      ++completedLines_;
      handleLine(pending_);
      clearPending();
    }
    if (inStatement_) {  // the last line ended with a continuation backslash
      inStatement_ = false;
      parseStatement(joined_, statementLine_);
    }
    // Nothing at all, or lines without a statement (comments and blank lines, however many).
    if (!anyContent_) fail(0, completedLines_ == 0 ? "empty file" : "no vertices or faces (only comments and blank lines)");
    if (mesh_.faceCount() == 0) fail(0, "no faces");
    checkForwardIndices();
    resolveTags();
    reportWarnings();
    return std::move(mesh_);
  }

 private:
  static constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

  [[noreturn]] void fail(int64_t line, const std::string& what) const { throw InputError(source_, line, what); }

  void flushHead() {
    headDone_ = true;
    consume(head_ == kUtf8Bom ? std::string_view() : std::string_view(head_));
  }

  // NUL bytes and control characters mean the file is not text: the lines before the first one
  // are parsed (an earlier error comes first), then the reader stops at the byte's line.
  void consume(std::string_view bytes) {
    const auto bad = std::find_if(bytes.begin(), bytes.end(), [](char ch) { return isBinaryByte(static_cast<unsigned char>(ch)); });
    splitLines(bytes.substr(0, size_t(bad - bytes.begin())));
    if (bad != bytes.end())
      fail(completedLines_ + 1, *bad == '\0' ? "binary data (NUL byte), not a text OBJ file"
                                             : "binary data (control character), not a text OBJ file");
    checkUnfinishedLine();
  }

  // Cuts lines at LF, CR or CRLF; the CR of a CRLF ends the line and its LF is skipped, also
  // when it comes in the next chunk.
  void splitLines(std::string_view bytes) {
    size_t pos = 0;
    if (skipLineFeed_ && !bytes.empty()) {
      if (bytes[0] == '\n') pos = 1;
      skipLineFeed_ = false;
    }
    while (pos < bytes.size()) {
      size_t end = pos;
      while (end < bytes.size() && bytes[end] != '\n' && bytes[end] != '\r') ++end;
      if (end == bytes.size()) {
        pending_.append(bytes.substr(pos));
        return;
      }
      std::string_view line = bytes.substr(pos, end - pos);
      if (!pending_.empty()) line = pending_.append(line);
      ++completedLines_;
      handleLine(line);
      clearPending();
      pos = end + 1;
      if (bytes[end] == '\r') {
        if (pos == bytes.size()) skipLineFeed_ = true;
        else if (bytes[pos] == '\n') ++pos;
      }
    }
  }

  // A line still being read whose first word is already known not to be a statement fails now,
  // so a long run of garbage without line ends is not collected first; its leading blanks are
  // dropped (they mean nothing), so a long run of blanks is not collected either. Each byte is
  // looked at about once however many chunks the line spans.
  void checkUnfinishedLine() {
    if (inStatement_ || keywordChecked_) return;
    size_t i = 0;
    while (i < pending_.size() && isBlank(pending_[i])) ++i;
    pending_.erase(0, i);
    size_t j = 0;
    while (j < pending_.size() && !isBlank(pending_[j]) && pending_[j] != '#') ++j;
    const std::string_view keyword(pending_.data(), j);
    if (j == pending_.size() && keyword.size() <= kLongestKeyword) return;  // may still grow into a keyword
    keywordChecked_ = true;
    if (!keyword.empty() && !isKnownStatement(keyword)) fail(completedLines_ + 1, "unknown statement " + quoted(keyword));
  }

  // A line is complete: the next one starts unchecked.
  void clearPending() {
    pending_.clear();
    keywordChecked_ = false;
  }

  // A trailing backslash continues the statement on the next line (OBJ spec); errors name the
  // statement's first line.
  void handleLine(std::string_view line) {
    if (continues(line)) {
      if (!inStatement_) {
        inStatement_ = true;
        statementLine_ = completedLines_;
        joined_.clear();
      }
      joined_.append(withoutContinuation(line)).push_back(' ');
      return;
    }
    if (inStatement_) {
      inStatement_ = false;
      joined_.append(line);
      parseStatement(joined_, statementLine_);
      return;
    }
    parseStatement(line, completedLines_);
  }

  void parseStatement(std::string_view statement, int64_t line) {
    Tokens tokens(withoutComment(statement));
    std::string_view keyword = tokens.next();
    if (keyword.empty()) return;
    anyContent_ = true;
    if (keyword == "v") {
      readVertex(tokens, line);
    } else if (keyword == "f" || keyword == "fo") {
      readFace(tokens, line);
    } else if (keyword == "l") {
      ++polylines_;
    } else if (keyword == "p") {
      ++pointStatements_;
    } else if (keyword == "t") {
      readTag(tokens, line);
    } else if (!isKnownStatement(keyword)) {
      fail(line, "unknown statement " + quoted(keyword));
    }
  }

  // A finite number (a leading '+' allowed) of magnitude at most kMaxObjCoordinate: squares and
  // long sums of such numbers stay finite. `what` names it in errors.
  double parseNumber(std::string_view token, int64_t line, const char* what) const {
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (first != last && *first == '+') ++first;  // from_chars refuses a leading '+'
    double value = 0;
    auto [ptr, ec] = std::from_chars(first, last, value);
    const std::string tooLarge = std::string(what) + " " + quoted(token) + " is too large (the limit is 1e150)";
    if (ec == std::errc::result_out_of_range) {
      // Overflow is an error; underflow to zero or a subnormal is harmless.
      std::string copy(first, last);
      value = std::strtod(copy.c_str(), nullptr);
      if (std::isinf(value)) fail(line, tooLarge);
      return value;
    }
    if (ec != std::errc() || ptr != last) fail(line, "malformed number " + quoted(token));
    if (std::isnan(value)) fail(line, std::string(what) + " is NaN");
    if (std::isinf(value)) fail(line, std::string(what) + " is infinite");
    if (std::abs(value) > kMaxObjCoordinate) fail(line, tooLarge);
    return value;
  }

  // [SECTION] v and f

  // v x y z [w] or v x y z r g b: the first three numbers are the position.
  void readVertex(Tokens& tokens, int64_t line) {
    double coords[3] = {0, 0, 0};
    int count = 0;
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
      double value = parseNumber(token, line, "coordinate");
      if (count < 3) coords[count] = value;
      ++count;
    }
    if (count < 3) fail(line, "vertex has " + std::to_string(count) + " coordinates (3 needed)");
    if (count > 7) fail(line, "vertex has " + std::to_string(count) + " numbers (at most 7 expected)");
    mesh_.points.emplace_back(coords[0], coords[1], coords[2]);
  }

  // One `f` vertex reference "i", "i/t", "i//n" or "i/t/n" -> 0-based vertex index. Positive
  // indices may refer to vertices defined later (checked in checkForwardIndices); negative ones
  // are relative to the vertices read so far and must resolve inside them.
  Index parseFaceIndex(std::string_view token, int64_t line) const {
    std::string_view number = token.substr(0, token.find('/'));
    constexpr uint64_t kMaxIndex = 0x7fffffff;  // Index is int32
    bool negative = false;
    uint64_t magnitude = 0;
    if (!parseDecimal(number, kMaxIndex, &negative, &magnitude)) fail(line, "malformed face index " + quoted(token));
    if (magnitude == 0) fail(line, "face index 0 (OBJ indices start at 1)");
    const uint64_t defined = mesh_.points.size();
    if (negative) {
      if (magnitude > defined)
        fail(line, "face index " + shortened(number) + " out of range (" + std::to_string(defined) + " vertices)");
      return static_cast<Index>(defined - magnitude);
    }
    if (magnitude > kMaxIndex) fail(line, "face index " + shortened(number) + " is too large");
    return static_cast<Index>(magnitude - 1);
  }

  void readFace(Tokens& tokens, int64_t line) {
    const size_t begin = mesh_.faceVerts.size();
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next())
      mesh_.faceVerts.push_back(parseFaceIndex(token, line));
    const size_t k = mesh_.faceVerts.size() - begin;
    if (k < 3) fail(line, "face has " + std::to_string(k) + " vertices (at least 3 needed)");
    // A vertex repeated in a face is OpenSubdiv's degenerate edge: refined as it does (manifold_split.h),
    // but where the face's corners at the vertex lie in one fan of it (no manifold split keeps that
    // surface): refused when the mesh is refined ("face repeats a vertex").
    mesh_.faceStart.push_back(static_cast<Index>(mesh_.faceVerts.size()));
    mesh_.faceLine.push_back(line);
  }

  // Positive indices may point forward; once all vertices are known every index must be in range.
  void checkForwardIndices() {
    const Index n = mesh_.vertexCount();
    referenced_.assign(n, 0);
    for (Index f = 0; f < mesh_.faceCount(); ++f) {
      for (Index c = mesh_.faceStart[f]; c < mesh_.faceStart[f + 1]; ++c) {
        const Index v = mesh_.faceVerts[c];
        if (v >= n)
          fail(mesh_.faceLine[f], "face index " + std::to_string(int64_t(v) + 1) + " out of range (" + std::to_string(n) + " vertices)");
        referenced_[v] = 1;
      }
    }
  }

  // [SECTION] t tags

  // A feature as its tag gave it: an edge (v1 >= 0), a vertex (v1 < 0) or a face, with the
  // tag's line for errors found once the whole file is known.
  struct TaggedItem {
    int64_t v0, v1;
    double sharpness;
    int64_t line;
  };

  // `t NAME ni/nf/ns` then ni integers, nf numbers and ns strings: the tag syntax of OpenSubdiv's
  // shapes (and tinyobjloader's tag_t). Ids are 0-based. Every count must match exactly.
  void readTag(Tokens& tokens, int64_t line) {
    const std::string_view name = tokens.next();
    if (name.empty()) fail(line, "tag without a name ('t NAME ni/nf/ns values...')");
    const std::string_view countsText = tokens.next();
    uint64_t counts[3] = {0, 0, 0};
    parseTagCounts(name, countsText, line, counts);
    tagValues_.clear();
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) tagValues_.push_back(token);
    const uint64_t expected = counts[0] + counts[1] + counts[2];
    if (tagValues_.size() != expected)
      fail(line, "tag " + quoted(name) + " has " + std::to_string(tagValues_.size()) + " values, its counts " +
                     std::string(countsText) + " say " + std::to_string(expected));
    const TagShape shape{name, counts[0], counts[1], counts[2], line};

    if (name == "crease") {
      // Pairs of vertex ids, one sharpness for all or one per edge.
      requireShape(shape, counts[0] >= 2 && counts[0] % 2 == 0 && (counts[1] == 1 || counts[1] == counts[0] / 2) && counts[2] == 0,
                   "2k/1/0 or 2k/k/0 (k edges as vertex id pairs, one sharpness or one per edge)");
      for (uint64_t e = 0; e < counts[0] / 2; ++e) {
        const int64_t a = tagId(shape, 2 * e, "vertex"), b = tagId(shape, 2 * e + 1, "vertex");
        if (a == b) fail(line, "tag 'crease': edge from vertex " + std::to_string(a) + " to itself");
        creaseItems_.push_back({a, b, tagSharpness(shape, counts[1] == 1 ? 0 : e), line});
      }
    } else if (name == "corner") {
      requireShape(shape, counts[0] >= 1 && (counts[1] == 1 || counts[1] == counts[0]) && counts[2] == 0,
                   "k/1/0 or k/k/0 (k vertex ids, one sharpness or one per vertex)");
      for (uint64_t i = 0; i < counts[0]; ++i)
        cornerItems_.push_back({tagId(shape, i, "vertex"), -1, tagSharpness(shape, counts[1] == 1 ? 0 : i), line});
    } else if (name == "hole") {
      requireShape(shape, counts[0] >= 1 && counts[1] == 0 && counts[2] == 0, "k/0/0 (k face ids)");
      for (uint64_t i = 0; i < counts[0]; ++i) holeItems_.push_back({tagId(shape, i, "face"), -1, 0, line});
    } else if (name == "interpolateboundary") {
      // OpenSubdiv's numbering (far_utils.h): 0 none, 1 edge and corner, 2 edge only.
      constexpr BoundaryInterpolation kRules[] = {BoundaryInterpolation::None, BoundaryInterpolation::EdgeAndCorner,
                                                  BoundaryInterpolation::EdgeOnly};
      mesh_.tags.boundary = kRules[tagChoice(shape, 3, "0 (none), 1 (edge and corner) or 2 (edge only)")];
    } else if (name == "creasemethod") {
      mesh_.tags.creaseMethod = tagWord(shape, "normal", "chaikin") == 0 ? CreaseMethod::Uniform : CreaseMethod::Chaikin;
    } else if (name == "smoothtriangles") {
      mesh_.tags.triangles = tagWord(shape, "catmark", "smooth") == 0 ? TriangleSubdivision::Catmark : TriangleSubdivision::Smooth;
    } else if (name == "facevaryinginterpolateboundary") {
      tagChoice(shape, 6, "0 to 5 (OpenSubdiv's FVAR_LINEAR_* rules)");
      ++faceVaryingTags_;
    } else if (name == "facevaryingpropagatecorners") {
      tagChoice(shape, 2, "0 or 1");
      ++faceVaryingTags_;
    } else if (name == "vertexedit" || name == "edgeedit" || name == "faceedit") {
      ++hierarchicalEditTags_;
    } else {
      if (unknownTags_++ == 0) firstUnknownTag_ = quoted(name) + " on line " + std::to_string(line);
    }
  }

  struct TagShape {
    std::string_view name;
    uint64_t ints, reals, strings;
    int64_t line;
  };

  // "ni/nf/ns": three decimal counts.
  void parseTagCounts(std::string_view name, std::string_view text, int64_t line, uint64_t counts[3]) const {
    constexpr uint64_t kMaxCount = uint64_t(1) << 40;  // saturates; the value count check refuses it
    std::string_view rest = text;
    for (int i = 0; i < 3; ++i) {
      const size_t slash = rest.find('/');
      const std::string_view part = rest.substr(0, i < 2 ? slash : std::string_view::npos);
      bool negative = false;
      if ((i < 2 && slash == std::string_view::npos) || !parseDecimal(part, kMaxCount, &negative, &counts[i]) || negative)
        fail(line, "tag " + quoted(name) + ": malformed counts " + quoted(text) + " (ni/nf/ns expected, e.g. 2/1/0)");
      if (i < 2) rest.remove_prefix(slash + 1);
    }
  }

  void requireShape(const TagShape& shape, bool ok, const char* expected) const {
    if (!ok)
      fail(shape.line, "tag " + quoted(shape.name) + " with counts " + std::to_string(shape.ints) + "/" + std::to_string(shape.reals) +
                           "/" + std::to_string(shape.strings) + ": expected " + expected);
  }

  // Integer value i of a tag as a 0-based id of a `kind` (range checked in resolveTags).
  int64_t tagId(const TagShape& shape, uint64_t i, const char* kind) const {
    const std::string_view token = tagValues_[i];
    constexpr uint64_t kMaxId = 0x7fffffff;
    bool negative = false;
    uint64_t magnitude = 0;
    if (!parseDecimal(token, kMaxId, &negative, &magnitude))
      fail(shape.line, "tag " + quoted(shape.name) + ": malformed " + kind + " id " + quoted(token));
    if (negative && magnitude > 0)
      fail(shape.line, "tag " + quoted(shape.name) + ": " + kind + " id " + shortened(token) + " is negative (tag ids are 0-based)");
    if (magnitude > kMaxId) fail(shape.line, "tag " + quoted(shape.name) + ": " + kind + " id " + shortened(token) + " is too large");
    return int64_t(magnitude);
  }

  // Number value i (after the integers) as a sharpness: finite and >= 0.
  double tagSharpness(const TagShape& shape, uint64_t i) const {
    const std::string_view token = tagValues_[shape.ints + i];
    const double s = parseNumber(token, shape.line, "sharpness");
    if (s < 0) fail(shape.line, "tag " + quoted(shape.name) + ": sharpness " + shortened(token) + " is negative");
    return s;
  }

  // A tag of shape 1/0/0 whose integer is one of 0..choices-1.
  size_t tagChoice(const TagShape& shape, uint64_t choices, const char* allowed) const {
    requireShape(shape, shape.ints == 1 && shape.reals == 0 && shape.strings == 0, "1/0/0");
    bool negative = false;
    uint64_t value = 0;
    if (!parseDecimal(tagValues_[0], choices, &negative, &value) || negative || value >= choices)
      fail(shape.line, "tag " + quoted(shape.name) + ": " + quoted(tagValues_[0]) + " is not " + allowed);
    return size_t(value);
  }

  // A tag of shape 0/0/1 whose string is `first` (0) or `second` (1).
  int tagWord(const TagShape& shape, std::string_view first, std::string_view second) const {
    requireShape(shape, shape.ints == 0 && shape.reals == 0 && shape.strings == 1, "0/0/1");
    if (tagValues_[0] == first) return 0;
    if (tagValues_[0] == second) return 1;
    fail(shape.line, "tag " + quoted(shape.name) + ": " + quoted(tagValues_[0]) + " is not '" + std::string(first) + "' or '" +
                         std::string(second) + "'");
  }

  // Checks every tagged id against the finished mesh (crease edges must be edges of a face) and
  // merges the tags into mesh_.tags: one entry per edge, vertex or face, the last tag winning.
  void resolveTags() {
    const int64_t vertices = mesh_.vertexCount(), faces = mesh_.faceCount();
    auto checkRange = [&](const char* tag, const TaggedItem& item, int64_t id, int64_t count, const char* kind, const char* kinds) {
      if (id >= count)
        fail(item.line, std::string("tag '") + tag + "': " + kind + " id " + std::to_string(id) + " out of range (" +
                            std::to_string(count) + " " + kinds + "; tag ids are 0-based)");
    };
    for (const TaggedItem& c : creaseItems_) {
      checkRange("crease", c, c.v0, vertices, "vertex", "vertices");
      checkRange("crease", c, c.v1, vertices, "vertex", "vertices");
    }
    for (const TaggedItem& c : cornerItems_) checkRange("corner", c, c.v0, vertices, "vertex", "vertices");
    for (const TaggedItem& h : holeItems_) checkRange("hole", h, h.v0, faces, "face", "faces");
    rejectCreasesOffTheMesh();

    // Merge: sort by id keeping file order among equals, keep the last of each run.
    auto lastOfEachId = [](std::vector<TaggedItem>& items, auto key) {
      std::stable_sort(items.begin(), items.end(), [&](const TaggedItem& a, const TaggedItem& b) { return key(a) < key(b); });
      std::vector<TaggedItem> kept;
      for (size_t i = 0; i < items.size(); ++i)
        if (i + 1 == items.size() || key(items[i + 1]) != key(items[i])) kept.push_back(items[i]);
      return kept;
    };
    SubdivTags& tags = mesh_.tags;
    for (const TaggedItem& c : lastOfEachId(creaseItems_, [](const TaggedItem& t) { return edgeKey(Index(t.v0), Index(t.v1)); }))
      if (c.sharpness > 0) tags.creases.push_back({Index(std::min(c.v0, c.v1)), Index(std::max(c.v0, c.v1)), c.sharpness});
    for (const TaggedItem& c : lastOfEachId(cornerItems_, [](const TaggedItem& t) { return t.v0; }))
      if (c.sharpness > 0) tags.corners.push_back({Index(c.v0), c.sharpness});
    for (const TaggedItem& h : lastOfEachId(holeItems_, [](const TaggedItem& t) { return t.v0; })) tags.holes.push_back(Index(h.v0));
  }

  // A crease tag on two vertices that no face has as neighbours is an error (OpenSubdiv refuses
  // it too); the earliest such tag is named. [O(corners log creases)]
  void rejectCreasesOffTheMesh() {
    if (creaseItems_.empty()) return;
    std::vector<uint64_t> keys;
    for (const TaggedItem& c : creaseItems_) keys.push_back(edgeKey(Index(c.v0), Index(c.v1)));
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<uint8_t> onMesh(keys.size(), 0);
    for (Index f = 0; f < mesh_.faceCount(); ++f) {
      const Index* loop = mesh_.face(f);
      const Index k = mesh_.faceSize(f);
      for (Index i = 0; i < k; ++i) {
        auto it = std::lower_bound(keys.begin(), keys.end(), edgeKey(loop[i], loop[(i + 1) % k]));
        if (it != keys.end() && *it == edgeKey(loop[i], loop[(i + 1) % k])) onMesh[size_t(it - keys.begin())] = 1;
      }
    }
    for (const TaggedItem& c : creaseItems_) {  // file order: the first offender is named
      const size_t i = size_t(std::lower_bound(keys.begin(), keys.end(), edgeKey(Index(c.v0), Index(c.v1))) - keys.begin());
      if (!onMesh[i])
        fail(c.line, "tag 'crease': vertices " + std::to_string(c.v0) + " and " + std::to_string(c.v1) +
                         " (0-based) are not an edge of any face");
    }
  }

  // [SECTION] Warnings

  void reportWarnings() {
    if (!warnings_) return;
    auto warn = [&](std::string text) { warnings_->push_back(std::move(text)); };
    const size_t unused = std::count(referenced_.begin(), referenced_.end(), uint8_t(0));
    if (unused > 0) warn(std::to_string(unused) + " unreferenced vertices ignored");
    if (polylines_ > 0) warn(std::to_string(polylines_) + " 'l' (polyline) statements ignored");
    if (pointStatements_ > 0) warn(std::to_string(pointStatements_) + " 'p' (point) statements ignored");
    // Where the tags are applied: Catmull-Clark's refinements (refiner.h, adaptive_refiner.h), whose
    // limit surface refines the faces at sharp features to the last level.
    const SubdivTags& tags = mesh_.tags;
    const char* kOnlyUniformCatmullClark =
        " Catmull-Clark's rules apply them in every scheme (a pole they touch is left to Catmull-Clark; faces at"
        " semi-sharp features are refined to the last level), except RTS/BPS's radial refinement of caps and globes";
    if (tags.hasSharpFeatures())
      warn(std::to_string(tags.creases.size()) + " crease edges and " + std::to_string(tags.corners.size()) + " corners ('t' tags):" +
           kOnlyUniformCatmullClark);
    if (tags.boundary == BoundaryInterpolation::EdgeAndCorner) warn(std::string("'t interpolateboundary 1' (sharp corners):") + kOnlyUniformCatmullClark);
    // Holes ('t hole', and the boundary faces of 't interpolateboundary 0') are applied by every
    // scheme: they give no patches (a pole touching one is left to Catmull-Clark).
    if (tags.triangles != TriangleSubdivision::Catmark)
      warn(std::string("'t smoothtriangles smooth' (OpenSubdiv's TRI_SUB_SMOOTH edge weights next to triangles):") +
           kOnlyUniformCatmullClark);
    if (faceVaryingTags_ > 0) warn(std::to_string(faceVaryingTags_) + " face-varying 't' tags ignored (polarview has no face-varying data)");
    if (hierarchicalEditTags_ > 0)
      warn(std::to_string(hierarchicalEditTags_) + " hierarchical-edit 't' tags ignored (OpenSubdiv 3 does not apply them either)");
    if (unknownTags_ > 0) warn(std::to_string(unknownTags_) + " 't' tags of unknown kind ignored (the first: " + firstUnknownTag_ + ")");
  }

  const std::string& source_;
  std::vector<std::string>* warnings_;
  PolyMesh mesh_;

  // Line assembly across chunks.
  std::string head_;             // the first bytes, until a byte-order mark is ruled in or out
  bool headDone_ = false;
  std::string pending_;          // the current line's bytes from earlier chunks
  bool keywordChecked_ = false;  // pending_'s first word is known to be a statement (or absent)
  bool skipLineFeed_ = false;    // the last chunk ended with a CR: an LF next belongs to it
  int64_t completedLines_ = 0;   // physical lines ended so far; 64-bit: files may pass 2^31 lines
  std::string joined_;           // a statement continued over lines so far
  bool inStatement_ = false;
  int64_t statementLine_ = 0;    // the continued statement's first line
  bool anyContent_ = false;

  std::vector<uint8_t> referenced_;
  std::vector<std::string_view> tagValues_;
  std::vector<TaggedItem> creaseItems_, cornerItems_, holeItems_;
  size_t polylines_ = 0, pointStatements_ = 0, faceVaryingTags_ = 0, hierarchicalEditTags_ = 0, unknownTags_ = 0;
  std::string firstUnknownTag_;
};

// [SECTION] Writing

// Appends `value` as the shortest text that reads back to the same double (to_chars without a
// format or precision: the fewest characters, fixed or scientific, that round-trip).
void appendNumber(std::string& out, double value) {
  char number[64];
  auto result = std::to_chars(number, number + sizeof number, value);
  out.append(number, result.ptr);
}

void appendInteger(std::string& out, int64_t value) {
  char number[32];
  auto result = std::to_chars(number, number + sizeof number, value);
  out.append(number, result.ptr);
}

// The `t` lines that give back `tags` when read (options only where they differ from the defaults).
std::string tagLines(const SubdivTags& tags) {
  std::string out;
  if (tags.boundary != BoundaryInterpolation::EdgeOnly)
    out += tags.boundary == BoundaryInterpolation::None ? "t interpolateboundary 1/0/0 0\n" : "t interpolateboundary 1/0/0 1\n";
  if (tags.creaseMethod == CreaseMethod::Chaikin) out += "t creasemethod 0/0/1 chaikin\n";
  if (tags.triangles == TriangleSubdivision::Smooth) out += "t smoothtriangles 0/0/1 smooth\n";
  for (const CreaseEdge& c : tags.creases) {
    out += "t crease 2/1/0 ";
    appendInteger(out, c.v0);
    out += ' ';
    appendInteger(out, c.v1);
    out += ' ';
    appendNumber(out, c.sharpness);
    out += '\n';
  }
  for (const CornerVertex& c : tags.corners) {
    out += "t corner 1/1/0 ";
    appendInteger(out, c.vertex);
    out += ' ';
    appendNumber(out, c.sharpness);
    out += '\n';
  }
  for (Index h : tags.holes) {
    out += "t hole 1/0/0 ";
    appendInteger(out, h);
    out += '\n';
  }
  return out;
}

// Whether two tag sets are the same (saveObjEdited keeps the source's `t` lines only for its own tags).
bool sameTags(const SubdivTags& a, const SubdivTags& b) {
  return a.creases == b.creases && a.corners == b.corners && a.holes == b.holes && a.boundary == b.boundary &&
         a.creaseMethod == b.creaseMethod && a.triangles == b.triangles;
}

// Whether two doubles are the same bit for bit (-0 is not 0: it reads back as -0).
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }
bool sameBits(const Point& a, const Point& b) { return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z); }

// A non-finite number would be written as "nan"/"inf", which no reader takes back: refused before
// anything is created.
void refuseNonFinite(const std::string& path, const PolyMesh& mesh, const std::string& sourceName) {
  const std::string& source = sourceName.empty() ? path : sourceName;
  for (size_t v = 0; v < mesh.points.size(); ++v) {
    const Point& p = mesh.points[v];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
    throw InputError(source, 0,
                     "the result has a non-finite coordinate (vertex " + std::to_string(v + 1) +
                         "): the input's coordinates are too large, too small or degenerate; " + path + " not written");
  }
  const auto badSharpness = [](double s) { return !std::isfinite(s) || s < 0; };
  if (std::any_of(mesh.tags.creases.begin(), mesh.tags.creases.end(), [&](const CreaseEdge& c) { return badSharpness(c.sharpness); }) ||
      std::any_of(mesh.tags.corners.begin(), mesh.tags.corners.end(), [&](const CornerVertex& c) { return badSharpness(c.sharpness); }))
    throw InputError(source, 0, "a crease or corner sharpness is negative or not finite; " + path + " not written");
}

// Text made in a buffer and handed to the stream in large blocks (one write per megabyte).
struct BufferedObjText {
  static constexpr size_t kFlushAt = size_t(1) << 20;
  std::ostream& stream;
  std::string out;

  explicit BufferedObjText(std::ostream& to) : stream(to) { out.reserve(kFlushAt + 256); }
  void flushIfFull() {
    if (out.size() < kFlushAt) return;
    flush();
  }
  void flush() {
    stream.write(out.data(), std::streamsize(out.size()));
    out.clear();
  }
};

// One statement of a source text as the reader cut it (one line, or lines joined by continuation
// backslashes): all its bytes with the line end, the statement the reader parsed (continuations
// joined as it joins them) and that line end.
struct SourceStatement {
  std::string_view bytes;      // empty at the end of the text
  std::string_view statement;  // points into the text, or into SourceStatements' joined copy
  std::string_view lineEnd;    // LF, CRLF, CR or nothing (the last line)
  bool isVertex = false;       // a `v` statement
};

// Walks an OBJ text statement by statement with the reader's own rules (ObjParser::splitLines and
// handleLine: LF, CRLF and a lone CR end lines, a trailing backslash continues the statement), so
// its n-th `v` statement is the mesh's vertex n. A leading byte-order mark comes as a piece of its
// own (no statement), so it stays when the first statement is rewritten.
class SourceStatements {
 public:
  explicit SourceStatements(std::string_view text) : text_(text) {}

  SourceStatement next() {
    SourceStatement s;
    const size_t begin = pos_;
    if (pos_ == 0 && text_.substr(0, 3) == "\xEF\xBB\xBF") {
      pos_ = 3;
      s.bytes = text_.substr(0, 3);
      return s;
    }
    if (pos_ >= text_.size()) return s;
    joined_.clear();
    for (;;) {
      const size_t lineBegin = pos_;
      size_t end = lineBegin;
      while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
      pos_ = end;
      if (pos_ < text_.size()) pos_ += (text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') ? 2 : 1;
      const std::string_view line = text_.substr(lineBegin, end - lineBegin);
      s.lineEnd = text_.substr(end, pos_ - end);
      const bool continuesHere = continues(line);
      if (!continuesHere && joined_.empty()) {
        s.statement = line;
        break;
      }
      // Joined as handleLine joins; a continuation on the last line continues into nothing.
      if (continuesHere) joined_.append(withoutContinuation(line)).push_back(' ');
      else joined_.append(line);
      if (!continuesHere || pos_ == text_.size()) {
        s.statement = joined_;
        break;
      }
    }
    s.bytes = text_.substr(begin, pos_ - begin);
    Tokens tokens(withoutComment(s.statement));
    s.isVertex = tokens.next() == "v";
    return s;
  }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  std::string joined_;
};

// Appends the `v` statement `statement` with the coordinates that differ from `before` replaced by
// `after`'s, shortest; everything else of it (spacing, w or colour fields, a comment) as it is.
void appendMovedVertex(std::string& out, std::string_view statement, const Point& before, const Point& after) {
  Tokens tokens(withoutComment(statement));
  tokens.next();  // "v"
  const char* copied = statement.data();
  for (int i = 0; i < 3; ++i) {
    const std::string_view token = tokens.next();
    if (sameBits(before[i], after[i])) continue;
    out.append(copied, token.data());
    appendNumber(out, after[i]);
    copied = token.data() + token.size();
  }
  out.append(copied, statement.data() + statement.size());
}

}  // namespace

PolyMesh parseObjText(const std::string& text, const std::string& sourceName, std::vector<std::string>* warnings) {
  ObjParser parser(sourceName, warnings);
  parser.feed(text);
  return parser.finish();
}

PolyMesh parseObj(std::istream& in, const std::string& sourceName, std::vector<std::string>* warnings) {
  ObjParser parser(sourceName, warnings);
  std::unique_ptr<char[]> buffer(new char[kReadChunk]);
  for (;;) {
    in.read(buffer.get(), std::streamsize(kReadChunk));
    const size_t got = size_t(in.gcount());
    if (got > 0) parser.feed(std::string_view(buffer.get(), got));
    if (!in) break;
  }
  if (in.bad()) throw InputError(sourceName, 0, "cannot read the file");
  return parser.finish();
}

PolyMesh loadObj(const std::string& path, std::vector<std::string>* warnings, std::string* text) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  ObjParser parser(path, warnings);
  std::unique_ptr<char[]> buffer(new char[kReadChunk]);
  size_t got = 0;
  if (text) text->clear();
  while ((got = std::fread(buffer.get(), 1, kReadChunk, file.get())) > 0) {
    if (text) text->append(buffer.get(), got);
    parser.feed(std::string_view(buffer.get(), got));
  }
  if (std::ferror(file.get())) throw InputError(path, 0, "cannot read the file (is it a directory?)");
  return parser.finish();
}

void writeObj(std::ostream& stream, const PolyMesh& mesh) {
  BufferedObjText file(stream);
  for (const Point& p : mesh.points) {
    file.out += 'v';
    for (int i = 0; i < 3; ++i) {
      file.out += ' ';
      appendNumber(file.out, p[i]);
    }
    file.out += '\n';
    file.flushIfFull();
  }
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    file.out += 'f';
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) {
      file.out += ' ';
      appendInteger(file.out, int64_t(mesh.faceVerts[c]) + 1);
    }
    file.out += '\n';
    file.flushIfFull();
  }
  file.out += tagLines(mesh.tags);
  file.flush();
}

void saveObj(const std::string& path, const PolyMesh& mesh, const std::string& sourceName) {
  refuseNonFinite(path, mesh, sourceName);
  writeFileAtomically(path, [&](std::ostream& out) { writeObj(out, mesh); });
}

namespace {
// The source text with the moved vertices' coordinates rewritten (saveObjEdited).
void writeObjEdited(std::ostream& stream, const PolyMesh& mesh, const PolyMesh& source, const std::string& sourceText) {
  BufferedObjText file(stream);
  SourceStatements statements(sourceText);
  Index vertex = 0;
  for (SourceStatement s = statements.next(); !s.bytes.empty(); s = statements.next()) {
    const bool moved = s.isVertex && !sameBits(mesh.points[size_t(vertex)], source.points[size_t(vertex)]);
    if (moved) {
      appendMovedVertex(file.out, s.statement, source.points[size_t(vertex)], mesh.points[size_t(vertex)]);
      file.out += s.lineEnd;
    } else {
      file.out += s.bytes;
    }
    if (s.isVertex) ++vertex;
    file.flushIfFull();
  }
  file.flush();
}
}  // namespace

bool saveObjEdited(const std::string& path, const PolyMesh& mesh, const std::string& sourceText, const std::string& sourceName) {
  // The source read again (it parsed when loaded): its points say which vertices moved, its faces
  // and tags whether `mesh` is still its mesh.
  const PolyMesh source = parseObjText(sourceText, sourceName.empty() ? path : sourceName);
  if (source.vertexCount() != mesh.vertexCount() || source.faceStart != mesh.faceStart || source.faceVerts != mesh.faceVerts ||
      !sameTags(source.tags, mesh.tags)) {
    saveObj(path, mesh, sourceName);
    return false;
  }
  refuseNonFinite(path, mesh, sourceName);
  writeFileAtomically(path, [&](std::ostream& out) { writeObjEdited(out, mesh, source, sourceText); });
  return true;
}

}  // namespace polarview
