// The Python module `polarview` (docs/python.md): numpy arrays in and out over the core and the
// pipeline. One file per topic: meshes (mesh_bindings.cpp), patches and their evaluation
// (patch_bindings.cpp), the analysis of poles, spectra and subdivision matrices
// (analysis_bindings.cpp), tessellations, surface files and the n-gon conversion
// (export_bindings.cpp); report trees as dicts (report_conversion.cpp); module.cpp joins them and
// maps errors to Python's. The package over it (python/polarview/__init__.py) checks the arguments.
#pragma once

#include <memory>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "core/mesh/poly_mesh.h"
#include "core/subdiv/scheme.h"
#include "pipeline/report_value.h"

namespace polarview::python {

namespace py = pybind11;

// A mesh as Python sees it: immutable once made (arrays hand out read-only views of it), and the
// name its errors give (the file it was read from, "<arrays>", "<refined>").
struct Mesh {
  std::shared_ptr<const PolyMesh> mesh;
  std::string source;
};

// "c2ps", "rts-u", ...: the scheme variant, or ValueError naming the ones there are. [O(1)]
SchemeVariant schemeArgument(const std::string& name);

// A read-only numpy view of `data` (shape and byte strides), kept alive by `owner`. [O(1)]
py::array readOnlyView(py::dtype dtype, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, const void* data,
                       py::handle owner);

// How a report's doubles become Python numbers. info() and pole() have always handed out what
// json.loads made of the CLI's text, where an integral double (printed without a point) is an int:
// AsInt keeps that. spectrum()'s c2ps dict has always held floats: AsFloat.
enum class IntegralNumbers { AsInt, AsFloat };
// A report tree as dicts (keys in order), lists, numbers, strings, bools and None. [O(size)]
py::object toPython(const ReportValue& value, IntegralNumbers integral);

void bindMeshes(py::module_& m);
void bindPatches(py::module_& m);
void bindAnalysis(py::module_& m);
void bindExport(py::module_& m);

}  // namespace polarview::python
