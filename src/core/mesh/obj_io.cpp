// Strict line-based OBJ reader and atomic OBJ writer (see obj_io.h).
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
#include <iterator>
#include <memory>
#include <string_view>

namespace polarview {

namespace {

bool isBlank(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v'; }

// Bytes that never occur in a text OBJ file: control characters other than whitespace, and DEL.
bool isBinaryByte(unsigned char ch) {
  if (ch == '\n' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v') return false;
  return ch < 0x20 || ch == 0x7f;
}

// Statements of the OBJ format polarview does not need (free-form geometry, grouping, materials,
// rendering attributes): skipped without a word. Anything else that is not v/f/l/p is an error.
bool isIgnoredStatement(std::string_view keyword) {
  static constexpr std::string_view kIgnored[] = {
      "vt", "vn", "vp", "g", "o", "s", "mg", "usemtl", "mtllib", "maplib", "usemap", "lod", "bevel",
      "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech", "stech", "cstype", "deg", "bmat",
      "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con"};
  return std::find(std::begin(kIgnored), std::end(kIgnored), keyword) != std::end(kIgnored);
}

// Whether a line ends (before trailing blanks and a CR) with a continuation backslash.
bool continues(std::string_view line) {
  size_t end = line.find_last_not_of(" \t\r");
  return end != std::string_view::npos && line[end] == '\\';
}
// The line up to its continuation backslash.
std::string_view withoutContinuation(std::string_view line) { return line.substr(0, line.find_last_of('\\')); }

// Cuts text into lines at LF, CRLF or a lone CR (old Mac files), counting them. A CRLF's CR stays
// on the line (it is a blank to the tokenizer); a lone CR ends it.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  bool done() const { return pos_ >= text_.size(); }
  int lineNumber() const { return lineNumber_; }
  // The next line, without its line end. [O(line length), amortised]
  std::string_view next() {
    // The next LF is found once and reused, so a file without any (CR-only) stays linear.
    if (!newlineKnown_ || newline_ < pos_) {
      newline_ = std::min(text_.find('\n', pos_), text_.size());
      newlineKnown_ = true;
    }
    size_t end = newline_;
    size_t next = end + 1;
    const size_t cr = text_.substr(pos_, end - pos_).find('\r');
    if (cr != std::string_view::npos && pos_ + cr + 1 < end) {  // a lone CR before the LF
      end = pos_ + cr;
      next = end + 1;
    }
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = next;
    ++lineNumber_;
    return line;
  }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  size_t newline_ = 0;  // the next LF at or after pos_ (text size when none), once known
  bool newlineKnown_ = false;
  int lineNumber_ = 0;
};

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

class ObjParser {
 public:
  ObjParser(const std::string& sourceName, std::vector<std::string>* warnings)
      : source_(sourceName), warnings_(warnings) {}

  PolyMesh parse(std::string_view text) {
    // A UTF-8 byte-order mark (Windows editors write one) is not part of the first statement.
    constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
    if (text.substr(0, kUtf8Bom.size()) == kUtf8Bom) text.remove_prefix(kUtf8Bom.size());
    rejectBinary(text);
    LineReader lines(text);
    bool anyContent = false;
    std::string joined;
    while (!lines.done()) {
      std::string_view line = lines.next();
      // A trailing backslash continues the statement on the next line (OBJ spec); errors name the
      // statement's first line.
      const int statementLine = lines.lineNumber();
      if (continues(line)) {
        joined.clear();
        while (continues(line) && !lines.done()) {
          joined.append(withoutContinuation(line)).push_back(' ');
          line = lines.next();
        }
        joined.append(continues(line) ? withoutContinuation(line) : line);
        line = joined;
      }
      size_t hash = line.find('#');  // comments run to the end of the line
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      Tokens tokens(line);
      std::string_view keyword = tokens.next();
      if (keyword.empty()) continue;
      anyContent = true;
      if (keyword == "v") {
        readVertex(tokens, statementLine);
      } else if (keyword == "f" || keyword == "fo") {
        readFace(tokens, statementLine);
      } else if (keyword == "l") {
        ++polylines_;
      } else if (keyword == "p") {
        ++pointStatements_;
      } else if (keyword == "t") {
        ++tags_;
      } else if (!isIgnoredStatement(keyword)) {
        fail(statementLine, "unknown statement " + quoted(keyword));
      }
    }
    if (!anyContent) fail(0, "empty file");
    if (mesh_.faceCount() == 0) fail(0, "no faces");
    checkForwardIndices();
    reportWarnings();
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& what) const { throw InputError(source_, line, what); }

  // NUL bytes and control characters mean the file is not text: refuse before parsing numbers.
  void rejectBinary(std::string_view text) const {
    auto bad = std::find_if(text.begin(), text.end(), [](char ch) { return isBinaryByte(static_cast<unsigned char>(ch)); });
    if (bad == text.end()) return;
    LineReader lines(text.substr(0, size_t(bad - text.begin())));
    while (!lines.done()) lines.next();
    const int line = lines.lineNumber() + (text.begin() == bad || bad[-1] == '\n' || bad[-1] == '\r' ? 1 : 0);
    fail(line, *bad == '\0' ? "binary data (NUL byte), not a text OBJ file" : "binary data (control character), not a text OBJ file");
  }

  double parseCoordinate(std::string_view token, int line) const {
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (first != last && *first == '+') ++first;  // from_chars refuses a leading '+'
    double value = 0;
    auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::result_out_of_range) {
      // Overflow is an error; underflow to zero or a subnormal is harmless.
      std::string copy(first, last);
      value = std::strtod(copy.c_str(), nullptr);
      if (std::isinf(value)) fail(line, "coordinate " + quoted(token) + " is too large (the limit is 1e150)");
      return value;
    }
    if (ec != std::errc() || ptr != last) fail(line, "malformed number " + quoted(token));
    if (std::isnan(value)) fail(line, "coordinate is NaN");
    if (std::isinf(value)) fail(line, "coordinate is infinite");
    if (std::abs(value) > kMaxObjCoordinate) fail(line, "coordinate " + quoted(token) + " is too large (the limit is 1e150)");
    return value;
  }

  // v x y z [w] or v x y z r g b: the first three numbers are the position.
  void readVertex(Tokens& tokens, int line) {
    double coords[3] = {0, 0, 0};
    int count = 0;
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
      double value = parseCoordinate(token, line);
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
  Index parseFaceIndex(std::string_view token, int line) const {
    std::string_view number = token.substr(0, token.find('/'));
    const bool negative = !number.empty() && number.front() == '-';
    std::string_view digits = number.substr(negative ? 1 : 0);
    if (digits.empty()) fail(line, "malformed face index " + quoted(token));
    // The magnitude as unsigned, stopping past the largest Index: no signed overflow, no
    // negation of an extreme value, whatever the digits.
    constexpr uint64_t kMaxIndex = 0x7fffffff;  // Index is int32
    uint64_t magnitude = 0;
    for (char ch : digits) {
      if (ch < '0' || ch > '9') fail(line, "malformed face index " + quoted(token));
      if (magnitude <= kMaxIndex) magnitude = magnitude * 10 + uint64_t(ch - '0');
    }
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

  void readFace(Tokens& tokens, int line) {
    const size_t begin = mesh_.faceVerts.size();
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next())
      mesh_.faceVerts.push_back(parseFaceIndex(token, line));
    const size_t k = mesh_.faceVerts.size() - begin;
    if (k < 3) fail(line, "face has " + std::to_string(k) + " vertices (at least 3 needed)");
    rejectRepeatedVertex(mesh_.faceVerts.data() + begin, k, line);
    mesh_.faceStart.push_back(static_cast<Index>(mesh_.faceVerts.size()));
    mesh_.faceLine.push_back(line);
  }

  void rejectRepeatedVertex(const Index* loop, size_t k, int line) {
    constexpr size_t kSmallFace = 16;  // pairwise check is fastest for ordinary faces
    Index repeated = -1;
    if (k <= kSmallFace) {
      for (size_t i = 0; i < k && repeated < 0; ++i)
        for (size_t j = i + 1; j < k; ++j)
          if (loop[i] == loop[j]) { repeated = loop[i]; break; }
    } else {
      scratch_.assign(loop, loop + k);
      std::sort(scratch_.begin(), scratch_.end());
      auto it = std::adjacent_find(scratch_.begin(), scratch_.end());
      if (it != scratch_.end()) repeated = *it;
    }
    if (repeated >= 0) fail(line, "face repeats vertex " + std::to_string(repeated + 1));
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

  void reportWarnings() {
    if (!warnings_) return;
    const size_t unused = std::count(referenced_.begin(), referenced_.end(), uint8_t(0));
    if (unused > 0) warnings_->push_back(std::to_string(unused) + " unreferenced vertices ignored");
    if (polylines_ > 0) warnings_->push_back(std::to_string(polylines_) + " 'l' (polyline) statements ignored");
    if (pointStatements_ > 0) warnings_->push_back(std::to_string(pointStatements_) + " 'p' (point) statements ignored");
    if (tags_ > 0) warnings_->push_back(std::to_string(tags_) + " 't' (OpenSubdiv crease/corner tag) statements ignored");
  }

  const std::string& source_;
  std::vector<std::string>* warnings_;
  PolyMesh mesh_;
  std::vector<Index> scratch_;
  std::vector<uint8_t> referenced_;
  size_t polylines_ = 0, pointStatements_ = 0, tags_ = 0;
};

}  // namespace

PolyMesh parseObjText(const std::string& text, const std::string& sourceName, std::vector<std::string>* warnings) {
  return ObjParser(sourceName, warnings).parse(text);
}

PolyMesh parseObj(std::istream& in, const std::string& sourceName, std::vector<std::string>* warnings) {
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(sourceName, 0, "cannot read the file");
  return parseObjText(text, sourceName, warnings);
}

PolyMesh loadObj(const std::string& path, std::vector<std::string>* warnings) {
  // Whole-file read with stdio: one allocation, no stream per token.
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, got);
  if (std::ferror(file.get())) throw InputError(path, 0, "cannot read the file (is it a directory?)");
  return parseObjText(text, path, warnings);
}

void saveObj(const std::string& path, const PolyMesh& mesh, const std::string& sourceName) {
  // A non-finite coordinate would be written as "nan"/"inf", which no reader takes back: refuse
  // before anything is created.
  for (size_t v = 0; v < mesh.points.size(); ++v) {
    const Point& p = mesh.points[v];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
    throw InputError(sourceName.empty() ? path : sourceName, 0,
                     "the result has a non-finite coordinate (vertex " + std::to_string(v + 1) +
                         "): the input's coordinates are too large or degenerate; " + path + " not written");
  }
  AtomicFileWriter file(path);

  // Format into a buffer with to_chars (%.17g equivalent) and write it in large blocks.
  std::string out;
  constexpr size_t kFlushAt = 1 << 20;
  out.reserve(kFlushAt + 256);
  char number[64];
  for (const Point& p : mesh.points) {
    out += 'v';
    for (int i = 0; i < 3; ++i) {
      auto result = std::to_chars(number, number + sizeof number, p[i], std::chars_format::general, 17);
      out += ' ';
      out.append(number, result.ptr);
    }
    out += '\n';
    if (out.size() >= kFlushAt) {
      file.write(out);
      out.clear();
    }
  }
  for (Index f = 0; f < mesh.faceCount(); ++f) {
    out += 'f';
    for (Index c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; ++c) {
      auto result = std::to_chars(number, number + sizeof number, int64_t(mesh.faceVerts[c]) + 1);
      out += ' ';
      out.append(number, result.ptr);
    }
    out += '\n';
    if (out.size() >= kFlushAt) {
      file.write(out);
      out.clear();
    }
  }
  file.write(out);
  file.commit();
}

}  // namespace polarview
