// A report as data: the objects, arrays and values a command's --json prints, kept as a tree. The
// CLI prints it (reportJson: JsonWriter's text, byte for byte) and the Python module hands it out as
// dicts and lists (python/report_conversion.cpp), so neither prints text for the other to parse.
// ReportBuilder makes a tree with JsonWriter's calls.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace polarview {

struct ReportValue {
  enum class Kind : uint8_t { Null, Bool, Integer, Number, Text, Array, Object };
  Kind kind = Kind::Null;
  bool flag = false;      // Bool
  long long integer = 0;  // Integer
  double number = 0.0;    // Number (finite: ReportBuilder refuses others)
  std::string text;       // Text
  std::vector<std::string> keys;   // Object: its keys in order
  std::vector<ReportValue> items;  // Array: its elements; Object: the values of `keys`

  // An object's member; throws std::out_of_range where there is none. [O(keys)]
  const ReportValue& operator[](const std::string& key) const;
};

// Builds a ReportValue with JsonWriter's calls: beginObject().field("a", 1).key("b").beginArray()...
class ReportBuilder {
 public:
  // `source` is the input file the numbers come from, named in the error a non-finite number raises.
  explicit ReportBuilder(std::string source = "") : source_(std::move(source)) {}
  ReportBuilder& beginObject() { return open(ReportValue::Kind::Object); }
  ReportBuilder& beginArray() { return open(ReportValue::Kind::Array); }
  ReportBuilder& endObject() { return close(); }
  ReportBuilder& endArray() { return close(); }
  ReportBuilder& key(const char* name);
  // As JsonWriter: a non-finite number throws InputError(source, 0, ...) naming the key.
  ReportBuilder& value(double x);
  ReportBuilder& value(long long x);
  ReportBuilder& value(int x) { return value(static_cast<long long>(x)); }
  ReportBuilder& value(size_t x) { return value(static_cast<long long>(x)); }
  ReportBuilder& value(bool b);
  ReportBuilder& value(const std::string& s);
  ReportBuilder& value(const char* s) { return value(std::string(s)); }
  ReportBuilder& null() { return add(ReportValue{}); }
  ReportBuilder& value(const glm::dvec3& p) { beginArray(); value(p.x).value(p.y).value(p.z); return endArray(); }
  template <class T>
  ReportBuilder& field(const char* name, const T& v) { key(name); return value(v); }
  // The finished tree (the builder is empty after). [O(1)]
  ReportValue take();

 private:
  ReportBuilder& open(ReportValue::Kind kind);
  ReportBuilder& close();
  ReportBuilder& add(ReportValue v);
  ReportValue root_;
  std::vector<ReportValue*> open_;  // the containers begun and not ended, innermost last
  std::string source_, lastKey_;
};

// The tree as JsonWriter writes it (one line, numbers round-trip). [O(size)]
std::string reportJson(const ReportValue& value);

}  // namespace polarview
