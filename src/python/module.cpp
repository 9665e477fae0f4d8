// PYBIND11_MODULE(_core): the bindings of each topic, and the errors Python sees: bad input
// (InputError, "FILE:LINE: what", as the CLI prints it after "polarview: ") is ValueError, a level
// over the memory budget (BudgetRefusal) MemoryError with the same text.
#include <pybind11/stl.h>

#include "core/mesh/input_error.h"
#include "pipeline/memory_budget.h"
#include "pipeline/scheme_choice.h"
#include "python/bindings.h"

namespace polarview::python {

SchemeVariant schemeArgument(const std::string& name) {
  const std::optional<SchemeVariant> variant = parseSchemeVariant(name);
  if (!variant) throw py::value_error("unknown scheme '" + name + "' (" + schemeChoiceNames(", ") + ")");
  return *variant;
}

py::array readOnlyView(py::dtype dtype, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, const void* data,
                       py::handle owner) {
  py::array view(std::move(dtype), std::move(shape), std::move(strides), data, owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

namespace {

// The scheme-choice table (pipeline/scheme_choice.h) in menu order: the names the package checks
// and lists, made from the scheme table rather than typed.
py::list schemeRows() {
  py::list rows;
  for (int i = 0; i < kSchemeChoiceCount; ++i) {
    const auto choice = static_cast<SchemeChoice>(i);
    const SchemeVariant variant = schemeChoiceVariant(choice);
    const SchemeTraits& traits = schemeTraits(variant.scheme);
    py::dict row;
    row["name"] = schemeChoiceCliName(choice), row["label"] = schemeChoiceLabel(choice);
    row["polar"] = traits.polar(), row["uniform_first_step"] = variant.uniformFirstStep;
    row["min_valence"] = traits.minValence;
    rows.append(row);
  }
  return rows;
}

}  // namespace

}  // namespace polarview::python

// The extension polarview._core; the package polarview (src/python/polarview/__init__.py) re-exports
// it with its arguments checked.
PYBIND11_MODULE(_core, m) {
  using namespace polarview::python;
  m.doc() = "C2PS polar subdivision surfaces (Myles & Peters 2009): meshes, refinement, limit patches, "
            "their evaluation and the analysis of poles; numpy arrays in and out (docs/python.md)";
  // Budget refusals first: BudgetRefusal is an InputError.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const polarview::BudgetRefusal& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    } catch (const polarview::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.def("schemes", &schemeRows, "the schemes in menu order: name, label, polar, uniform_first_step, min_valence");
  m.def("scheme_name", [](const std::string& name) { return schemeVariantName(schemeArgument(name)); }, py::arg("name"),
        "the command-line name of a scheme name (any case, aliases such as catmull-clark), else ValueError");
  bindMeshes(m);
  bindPatches(m);
  bindAnalysis(m);
  bindExport(m);
}
