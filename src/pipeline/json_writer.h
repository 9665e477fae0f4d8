// A minimal JSON writer for the CLI's machine-readable output (numbers round-trip doubles); the
// reports the Python module shares are trees (report_value.h) printed through it.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <glm/vec3.hpp>

#include "core/mesh/input_error.h"

namespace polarview {

class JsonWriter {
 public:
  // `source` is the input file the numbers come from, named in the error a non-finite number raises.
  explicit JsonWriter(std::string source = "") : source_(std::move(source)) {}
  JsonWriter& beginObject() { separate(); out_ += '{'; first_ = true; return *this; }
  JsonWriter& endObject() { out_ += '}'; first_ = false; return *this; }
  JsonWriter& beginArray() { separate(); out_ += '['; first_ = true; return *this; }
  JsonWriter& endArray() { out_ += ']'; first_ = false; return *this; }
  JsonWriter& key(const char* name) { separate(); out_ += quote(name) + ':'; first_ = true; lastKey_ = name; return *this; }
  // JSON has no inf or NaN, and printing null for a value that overflowed would hide the failure:
  // throws InputError(source, 0, ...) naming the key.
  JsonWriter& value(double x) {
    if (!std::isfinite(x)) throw nonFiniteError(source_, lastKey_);
    separate();
    out_ += number(x);
    return *this;
  }
  JsonWriter& value(long long x) { separate(); out_ += std::to_string(x); return *this; }
  JsonWriter& value(int x) { return value(static_cast<long long>(x)); }
  JsonWriter& value(size_t x) { return value(static_cast<long long>(x)); }
  JsonWriter& value(bool b) { separate(); out_ += b ? "true" : "false"; return *this; }
  JsonWriter& value(const std::string& s) { separate(); out_ += quote(s); return *this; }
  JsonWriter& value(const char* s) { return value(std::string(s)); }
  JsonWriter& null() { separate(); out_ += "null"; return *this; }
  JsonWriter& value(const glm::dvec3& p) { beginArray(); value(p.x).value(p.y).value(p.z); return endArray(); }
  template <class T>
  JsonWriter& field(const char* name, const T& v) { key(name); return value(v); }
  const std::string& str() const { return out_; }

  // The error a non-finite number under `key` raises (ReportBuilder raises it too).
  static InputError nonFiniteError(const std::string& source, const std::string& key) {
    return InputError(source, 0, "the result has a non-finite number (\"" + key +
                                     "\"): the input's coordinates are too large, too small or degenerate");
  }

  // 17 significant digits (round-trips a double); NaN/inf become null (value() refuses them first).
  static std::string number(double x) {
    if (!std::isfinite(x)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
  }
  static std::string quote(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') { q += '\\'; q += c; }
      else if (static_cast<unsigned char>(c) < 0x20) { char buf[8]; std::snprintf(buf, sizeof buf, "\\u%04x", c); q += buf; }
      else q += c;
    }
    return q + '"';
  }

 private:
  void separate() {
    if (!first_ && !out_.empty() && out_.back() != '[' && out_.back() != '{' && out_.back() != ':') out_ += ',';
    first_ = false;
  }
  std::string source_, lastKey_;
  std::string out_;
  bool first_ = true;
};

}  // namespace polarview
