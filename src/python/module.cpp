// PYBIND11_MODULE(polarview): the bindings of each topic, and the errors Python sees: bad input
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

py::object parseJson(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

}  // namespace polarview::python

PYBIND11_MODULE(polarview, m) {
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
  bindMeshes(m);
  bindPatches(m);
  bindAnalysis(m);
}
