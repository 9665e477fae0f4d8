// Reports as trees (see report_value.h).
#include "pipeline/report_value.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "pipeline/json_writer.h"

namespace polarview {

const ReportValue& ReportValue::operator[](const std::string& key) const {
  for (size_t i = 0; i < keys.size(); ++i)
    if (keys[i] == key) return items[i];
  throw std::out_of_range("report has no member \"" + key + "\"");
}

ReportBuilder& ReportBuilder::key(const char* name) {
  open_.back()->keys.push_back(name);
  lastKey_ = name;
  return *this;
}

ReportBuilder& ReportBuilder::value(double x) {
  if (!std::isfinite(x)) throw JsonWriter::nonFiniteError(source_, lastKey_);
  ReportValue v;
  v.kind = ReportValue::Kind::Number, v.number = x;
  return add(std::move(v));
}

ReportBuilder& ReportBuilder::value(long long x) {
  ReportValue v;
  v.kind = ReportValue::Kind::Integer, v.integer = x;
  return add(std::move(v));
}

ReportBuilder& ReportBuilder::value(bool b) {
  ReportValue v;
  v.kind = ReportValue::Kind::Bool, v.flag = b;
  return add(std::move(v));
}

ReportBuilder& ReportBuilder::value(const std::string& s) {
  ReportValue v;
  v.kind = ReportValue::Kind::Text, v.text = s;
  return add(std::move(v));
}

// Only the innermost open container grows, so the pointers to the outer ones stay valid.
ReportBuilder& ReportBuilder::add(ReportValue v) {
  if (open_.empty()) root_ = std::move(v);
  else open_.back()->items.push_back(std::move(v));
  return *this;
}

ReportBuilder& ReportBuilder::open(ReportValue::Kind kind) {
  ReportValue container;
  container.kind = kind;
  add(std::move(container));
  open_.push_back(open_.empty() ? &root_ : &open_.back()->items.back());
  return *this;
}

ReportBuilder& ReportBuilder::close() {
  open_.pop_back();
  return *this;
}

ReportValue ReportBuilder::take() {
  ReportValue out = std::move(root_);
  root_ = {};
  open_.clear();
  return out;
}

namespace {

void write(JsonWriter& w, const ReportValue& v) {
  switch (v.kind) {
    case ReportValue::Kind::Null: w.null(); break;
    case ReportValue::Kind::Bool: w.value(v.flag); break;
    case ReportValue::Kind::Integer: w.value(v.integer); break;
    case ReportValue::Kind::Number: w.value(v.number); break;
    case ReportValue::Kind::Text: w.value(v.text); break;
    case ReportValue::Kind::Array:
      w.beginArray();
      for (const ReportValue& item : v.items) write(w, item);
      w.endArray();
      break;
    case ReportValue::Kind::Object:
      w.beginObject();
      for (size_t i = 0; i < v.keys.size(); ++i) {
        w.key(v.keys[i].c_str());
        write(w, v.items[i]);
      }
      w.endObject();
      break;
  }
}

}  // namespace

std::string reportJson(const ReportValue& value) {
  JsonWriter w;
  write(w, value);
  return w.str();
}

}  // namespace polarview
