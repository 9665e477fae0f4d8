// Report trees (pipeline/report_value.h) as Python dicts, lists and numbers.
#include "python/bindings.h"

#include <cmath>

namespace polarview::python {

namespace {

// What json.loads made of JsonWriter's "%.17g": a double that prints without a point or an exponent
// (an integral value under 1e17) read back as an int; %.17g round-trips, so no other double does.
py::object number(double x, IntegralNumbers integral) {
  if (integral == IntegralNumbers::AsInt && x == std::trunc(x) && std::abs(x) < 1e17)
    return py::int_(static_cast<long long>(x));
  return py::float_(x);
}

}  // namespace

py::object toPython(const ReportValue& v, IntegralNumbers integral) {
  switch (v.kind) {
    case ReportValue::Kind::Null: return py::none();
    case ReportValue::Kind::Bool: return py::bool_(v.flag);
    case ReportValue::Kind::Integer: return py::int_(v.integer);
    case ReportValue::Kind::Number: return number(v.number, integral);
    case ReportValue::Kind::Text: return py::str(v.text);
    case ReportValue::Kind::Array: {
      py::list items;
      for (const ReportValue& item : v.items) items.append(toPython(item, integral));
      return std::move(items);
    }
    case ReportValue::Kind::Object: {
      py::dict members;
      for (size_t i = 0; i < v.keys.size(); ++i) members[py::str(v.keys[i])] = toPython(v.items[i], integral);
      return std::move(members);
    }
  }
  return py::none();
}

}  // namespace polarview::python
