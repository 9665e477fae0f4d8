// The limit surface as a triangle mesh and as files: tessellate() (the watertight mesh `polarview
// export OUT.ply` writes, as arrays), export_surface() (every format of `polarview export`, through
// the same table) and ngon_to_fan() (`polarview convert --ngon-to-fan`). The Blender add-on
// (src/blender) is built on these.
#include <cstring>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "core/export/tessellation.h"
#include "core/mesh/input_error.h"
#include "core/mesh/ngon_to_fan.h"
#include "pipeline/model.h"
#include "pipeline/patch_export.h"
#include "pipeline/surface_export.h"
#include "python/bindings.h"

namespace polarview::python {

namespace {

// The patches `polarview export` makes: feature-adaptive (or uniform) refinement within the budget,
// the mesh checked for curvature first as export does for ply and glb.
PatchSet exportPatches(const Mesh& m, const SchemeVariant& variant, int level, bool uniform, size_t memoryBudget) {
  if (level < 0 || level > 64) throw py::value_error("level must be in 0..64");
  const RefineOptions options{variant.scheme, level, variant.uniformFirstStep};
  const RefineRequest request =
      RefineRequest::withinMemory(options, uniform ? RefinePath::Uniform : RefinePath::FeatureAdaptive, memoryBudget);
  return makePatchSet(*m.mesh, m.source, request);
}

// A vector of rows as a fresh (n, width) numpy array of T, filled by `put(row, out)`.
template <typename T, typename Row, typename Put>
py::array_t<T> rows(const std::vector<Row>& in, py::ssize_t width, Put put) {
  py::array_t<T> out(width == 0 ? std::vector<py::ssize_t>{py::ssize_t(in.size())}
                                : std::vector<py::ssize_t>{py::ssize_t(in.size()), width});
  T* x = out.mutable_data();
  for (const Row& row : in) x = put(row, x);
  return out;
}

py::dict tessellate(const Mesh& m, const std::string& scheme, int level, int samples, bool uniform, size_t memoryBudget) {
  if (samples < 1 || samples > 64) throw py::value_error("samples must be in 1..64");
  const SchemeVariant variant = schemeArgument(scheme);
  Tessellation mesh;
  TessellationColouring colouring;
  TessellationEdges edges;
  {
    py::gil_scoped_release unlocked;
    requireCurvatureExtent(*m.mesh, m.source);
    const PatchSet set = exportPatches(m, variant, level, uniform, memoryBudget);
    checkTessellationBudget(set, samples, memoryBudget, m.source);
    mesh = tessellatePatchSet(set, samples);
    colouring = colourTessellation(mesh, set);
    edges = countTessellationEdges(mesh);
  }
  const auto point = [](const Point& p, double* x) {
    x[0] = p.x, x[1] = p.y, x[2] = p.z;
    return x + 3;
  };
  py::dict d;
  d["positions"] = rows<double>(mesh.positions, 3, point);
  d["normals"] = rows<double>(mesh.normals, 3, point);
  d["gaussian"] = rows<double>(mesh.gaussian, 0, [](double k, double* x) { *x = k; return x + 1; });
  d["mean"] = rows<double>(mesh.mean, 0, [](double h, double* x) { *x = h; return x + 1; });
  d["triangles"] = rows<uint32_t>(mesh.triangles, 3, [](const std::array<uint32_t, 3>& t, uint32_t* x) {
    std::memcpy(x, t.data(), sizeof t);
    return x + 3;
  });
  d["colours"] = rows<float>(colouring.colours, 3, [](const glm::vec3& c, float* x) {
    x[0] = c.x, x[1] = c.y, x[2] = c.z;
    return x + 3;
  });
  d["colour_range"] = py::make_tuple(colouring.range.low, colouring.range.high);
  d["patch"] = rows<uint32_t>(mesh.sources, 0, [](const TessellationSource& s, uint32_t* x) { *x = s.patch; return x + 1; });
  d["uv"] = rows<double>(mesh.sources, 2, [](const TessellationSource& s, double* x) {
    x[0] = s.u, x[1] = s.v;
    return x + 2;
  });
  d["boundary_edges"] = edges.boundary, d["non_manifold_edges"] = edges.nonManifold;
  d["misoriented_edges"] = edges.misoriented, d["watertight"] = edges.watertight();
  d["samples"] = samples, d["scheme"] = schemeVariantName(variant), d["level"] = level;
  return d;
}

// The row of the export table for `format` (a name), else for the path's extension.
const ExportFormat& exportFormat(const std::string& path, const std::string& format) {
  if (!format.empty()) {
    if (const ExportFormat* row = exportFormatNamed(format)) return *row;
    throw py::value_error("format must be one of " + exportFormatNames() + ", got '" + format + "'");
  }
  if (const ExportFormat* row = exportFormatForPath(path)) return *row;
  throw py::value_error("cannot tell the format of '" + path + "': name it " + exportFormatExtensions() +
                        " or give format=");
}

LengthUnit lengthUnit(const std::string& name) {
  std::string names;
  for (const LengthUnitInfo& unit : lengthUnits()) {
    if (name == unit.name) return unit.unit;
    names += std::string(names.empty() ? "" : ", ") + unit.name;
  }
  throw py::value_error("units must be one of " + names + ", got '" + name + "'");
}

std::string exportSurface(const Mesh& m, const std::string& path, const std::string& scheme, int level,
                          const std::string& format, int samples, const std::string& units, bool uniform,
                          size_t memoryBudget) {
  if (samples < 1 || samples > 64) throw py::value_error("samples must be in 1..64");
  const SchemeVariant variant = schemeArgument(scheme);
  const ExportFormat& row = exportFormat(path, format);
  ExportSettings settings;  // as runExport (src/app/cli_commands.cpp)
  settings.source = m.source;
  settings.units = lengthUnit(units);
  settings.samples = samples;
  settings.memoryBudget = memoryBudget;
  settings.level = level;
  settings.schemeLabel = schemeName(variant.scheme);
  py::gil_scoped_release unlocked;
  if (row.curvature) requireCurvatureExtent(*m.mesh, m.source);
  const PatchSet set = exportPatches(m, variant, level, uniform, memoryBudget);
  return exportSummary(writeSurfaceFile(path, set, row, settings));
}

py::tuple ngonToFan(const Mesh& m, int minSides) {
  if (minSides < 3) throw py::value_error("min_sides must be at least 3");
  FanConversion converted = convertNgonsToFans(*m.mesh, minSides);
  const std::vector<Index> centres = converted.centres;
  Mesh out{std::make_shared<const PolyMesh>(std::move(converted.mesh)), m.source};
  return py::make_tuple(py::cast(out), py::cast(centres));
}

}  // namespace

void bindExport(py::module_& m) {
  m.def("tessellate", &tessellate, py::arg("mesh"), py::arg("scheme") = "c2ps", py::arg("level") = 3,
        py::arg("samples") = 8, py::arg("uniform") = false, py::arg("memory_budget") = 0,
        "the watertight triangle mesh `polarview export OUT.ply` writes, as arrays: positions, normals, "
        "gaussian, mean, triangles, colours, colour_range, patch, uv, edge counts");
  m.def("export_surface", &exportSurface, py::arg("mesh"), py::arg("path"), py::arg("scheme") = "c2ps",
        py::arg("level") = 3, py::arg("format") = "", py::arg("samples") = 8, py::arg("units") = "mm",
        py::arg("uniform") = false, py::arg("memory_budget") = 0,
        "writes the limit surface as `polarview export` does (format from the extension or format=); "
        "returns the summary line");
  m.def("ngon_to_fan", &ngonToFan, py::arg("mesh"), py::arg("min_sides") = kMinFanSides,
        "`polarview convert --ngon-to-fan`: (mesh, centres), every face of min_sides or more corners a "
        "triangle fan around a new centre vertex");
}

}  // namespace polarview::python
