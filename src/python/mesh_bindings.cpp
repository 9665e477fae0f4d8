// Meshes: load(), Mesh(V, F), their arrays (read-only views), info(), save(), shape() and refine().
#include <cmath>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "core/mesh/input_error.h"
#include "core/mesh/obj_io.h"
#include "core/mesh/sharp_features.h"
#include "core/mesh/shape_catalog.h"
#include "core/subdiv/refiner.h"
#include "pipeline/memory_budget.h"
#include "pipeline/patch_export.h"
#include "pipeline/mesh_report.h"
#include "python/bindings.h"

namespace polarview::python {

namespace {

static_assert(sizeof(Point) == 3 * sizeof(double), "vertex views read Point as 3 packed doubles");
constexpr const char* kArraySource = "<arrays>";

Mesh wrap(PolyMesh mesh, std::string source) { return {std::make_shared<const PolyMesh>(std::move(mesh)), std::move(source)}; }

// The vertices of Mesh(V, F): (N, 3), finite and within the OBJ reader's range (obj_io.h).
std::vector<Point> verticesFromArray(const py::array_t<double, py::array::c_style | py::array::forcecast>& v) {
  if (v.ndim() != 2 || v.shape(1) != 3) throw InputError(kArraySource, 0, "vertices must be an (N, 3) array");
  if (v.shape(0) == 0) throw InputError(kArraySource, 0, "no vertices");
  std::vector<Point> points(size_t(v.shape(0)));
  const double* x = v.data();
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double value = x[3 * i + size_t(c)];
      if (!std::isfinite(value) || std::abs(value) > kMaxObjCoordinate)
        throw InputError(kArraySource, 0, "vertex " + std::to_string(i) + " has a coordinate that is " +
                                              (std::isnan(value) ? "NaN" : std::isinf(value) ? "infinite" : "too large") +
                                              " (finite, at most 1e150 in magnitude)");
      points[i][c] = value;
    }
  }
  return points;
}

// Faces of Mesh(V, F): an (M, k) array, or flat indices with a sizes array; 0-based, >= 3 a face.
void addFaces(PolyMesh& mesh, const py::array_t<int64_t, py::array::c_style | py::array::forcecast>& faces,
              const std::optional<py::array_t<int64_t, py::array::c_style | py::array::forcecast>>& sizes) {
  std::vector<int64_t> faceSizes;
  if (faces.ndim() == 2 && !sizes) faceSizes.assign(size_t(faces.shape(0)), faces.shape(1));
  else if (faces.ndim() == 1 && sizes && sizes->ndim() == 1) faceSizes.assign(sizes->data(), sizes->data() + sizes->size());
  else throw InputError(kArraySource, 0, "faces must be an (M, k) array, or flat indices with a sizes array");
  if (faceSizes.empty()) throw InputError(kArraySource, 0, "no faces");
  const int64_t* index = faces.data();
  int64_t used = 0;
  for (size_t f = 0; f < faceSizes.size(); ++f) {
    const int64_t k = faceSizes[f];
    if (k < 3) throw InputError(kArraySource, 0, "face " + std::to_string(f) + " has " + std::to_string(k) + " vertices (at least 3 needed)");
    if (used + k > faces.size()) throw InputError(kArraySource, 0, "the sizes add up to more than the indices given");
    std::vector<Index> loop(static_cast<size_t>(k));
    for (int64_t c = 0; c < k; ++c, ++used) {
      if (index[used] < 0 || index[used] >= mesh.vertexCount())
        throw InputError(kArraySource, 0, "face " + std::to_string(f) + ": vertex index " + std::to_string(index[used]) +
                                              " out of range (" + std::to_string(mesh.vertexCount()) + " vertices, 0-based)");
      loop[size_t(c)] = Index(index[used]);
    }
    mesh.addFace(loop.data(), loop.size());
  }
  if (used != faces.size()) throw InputError(kArraySource, 0, "the sizes add up to fewer than the indices given");
}

using IntArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Mesh(..., crease_edges=(E, 2), crease_sharpness=(E,), corners=(C,), corner_sharpness=(C,)): the
// tags an OBJ's `t crease` / `t corner` lines give (sharp_features.h).
void setTagsFromArrays(PolyMesh& mesh, const std::optional<IntArray>& creaseEdges, const std::optional<RealArray>& creaseSharpness,
                       const std::optional<IntArray>& corners, const std::optional<RealArray>& cornerSharpness) {
  if (creaseEdges.has_value() != creaseSharpness.has_value())
    throw InputError(kArraySource, 0, "crease_edges and crease_sharpness go together");
  if (corners.has_value() != cornerSharpness.has_value()) throw InputError(kArraySource, 0, "corners and corner_sharpness go together");
  auto id = [](int64_t v) { return v < 0 || v > int64_t(INT32_MAX) ? Index(-1) : Index(v); };  // out of range: refused below
  std::vector<CreaseEdge> creases;
  if (creaseEdges) {
    if (creaseEdges->ndim() != 2 || creaseEdges->shape(1) != 2 || creaseSharpness->ndim() != 1 ||
        creaseSharpness->shape(0) != creaseEdges->shape(0))
      throw InputError(kArraySource, 0, "crease_edges must be (E, 2) vertex ids with crease_sharpness (E,)");
    for (py::ssize_t e = 0; e < creaseEdges->shape(0); ++e)
      creases.push_back({id(creaseEdges->at(e, 0)), id(creaseEdges->at(e, 1)), creaseSharpness->at(e)});
  }
  std::vector<CornerVertex> cornerList;
  if (corners) {
    if (corners->ndim() != 1 || cornerSharpness->ndim() != 1 || cornerSharpness->shape(0) != corners->shape(0))
      throw InputError(kArraySource, 0, "corners must be (C,) vertex ids with corner_sharpness (C,)");
    for (py::ssize_t c = 0; c < corners->shape(0); ++c) cornerList.push_back({id(corners->at(c)), cornerSharpness->at(c)});
  }
  setSharpFeatures(mesh, creases, cornerList, kArraySource);
}

Mesh meshFromArrays(const RealArray& v, const IntArray& f, const std::optional<IntArray>& sizes,
                    const std::optional<IntArray>& creaseEdges, const std::optional<RealArray>& creaseSharpness,
                    const std::optional<IntArray>& corners, const std::optional<RealArray>& cornerSharpness) {
  PolyMesh mesh;
  mesh.points = verticesFromArray(v);
  addFaces(mesh, f, sizes);
  setTagsFromArrays(mesh, creaseEdges, creaseSharpness, corners, cornerSharpness);
  return wrap(std::move(mesh), kArraySource);
}

Mesh loadMesh(const std::string& path) {
  std::vector<std::string> warnings;
  PolyMesh mesh = loadObj(path, &warnings);
  for (const std::string& w : warnings)
    PyErr_WarnEx(PyExc_UserWarning, ("polarview: warning: " + path + ": " + w).c_str(), 1);
  return wrap(std::move(mesh), path);
}

// The faces as (flat indices, sizes): indices a view, sizes counted.
py::tuple faceArrays(py::object self) {
  const PolyMesh& mesh = *self.cast<const Mesh&>().mesh;
  py::array indices = readOnlyView(py::dtype::of<Index>(), {py::ssize_t(mesh.faceVerts.size())}, {sizeof(Index)},
                                   mesh.faceVerts.data(), self);
  py::array_t<Index> sizes(mesh.faceCount());
  for (Index f = 0; f < mesh.faceCount(); ++f) sizes.mutable_at(f) = mesh.faceSize(f);
  return py::make_tuple(indices, sizes);
}

// All-quad meshes: the faces as an (M, 4) view.
py::array quadArray(py::object self) {
  const PolyMesh& mesh = *self.cast<const Mesh&>().mesh;
  if (mesh.faceVerts.size() != 4 * size_t(mesh.faceCount())) throw py::value_error("not every face is a quad: use .faces");
  return readOnlyView(py::dtype::of<Index>(), {mesh.faceCount(), 4}, {4 * sizeof(Index), sizeof(Index)}, mesh.faceVerts.data(),
                      self);
}

py::dict tagsDict(const Mesh& m) {
  const SubdivTags& tags = m.mesh->tags;
  py::array_t<Index> edges({py::ssize_t(tags.creases.size()), py::ssize_t(2)});
  py::array_t<double> edgeSharpness(static_cast<py::ssize_t>(tags.creases.size()));
  for (size_t e = 0; e < tags.creases.size(); ++e) {
    edges.mutable_at(e, 0) = tags.creases[e].v0, edges.mutable_at(e, 1) = tags.creases[e].v1;
    edgeSharpness.mutable_at(e) = tags.creases[e].sharpness;
  }
  py::array_t<Index> corners(static_cast<py::ssize_t>(tags.corners.size()));
  py::array_t<double> cornerSharpness(static_cast<py::ssize_t>(tags.corners.size()));
  for (size_t c = 0; c < tags.corners.size(); ++c)
    corners.mutable_at(c) = tags.corners[c].vertex, cornerSharpness.mutable_at(c) = tags.corners[c].sharpness;
  py::dict d;
  d["crease_edges"] = edges, d["crease_sharpness"] = edgeSharpness;
  d["corners"] = corners, d["corner_sharpness"] = cornerSharpness;
  d["holes"] = py::array_t<Index>(py::ssize_t(tags.holes.size()), tags.holes.data());
  return d;
}

Mesh refineMesh(const Mesh& m, const std::string& scheme, int levels, size_t memoryBudget) {
  if (levels < 0 || levels > 64) throw py::value_error("levels must be in 0..64");
  const SchemeVariant variant = schemeArgument(scheme);
  const RefineRequest request =
      RefineRequest::withinMemory({variant.scheme, levels, variant.uniformFirstStep}, RefinePath::Uniform, memoryBudget);
  py::gil_scoped_release unlocked;
  return wrap(makeRefinedMesh(*m.mesh, m.source, request), m.source);  // as `polarview refine` writes
}

Mesh namedShape(const std::string& name, std::optional<int> valence, std::optional<int> links, const std::string& height) {
  shapes::ShapeRequest request{name, height, valence.value_or(12), links.value_or(6), valence || links};
  if (request.valence < 3 || request.valence > (1 << 20)) throw py::value_error("valence must be in 3..2^20");
  if (request.links < 1 || request.links > (1 << 16)) throw py::value_error("links must be in 1..2^16");
  return wrap(shapes::makeNamedShape(request), "<shape " + name + ">");
}

}  // namespace

void bindMeshes(py::module_& m) {
  py::class_<Mesh>(m, "Mesh", "A polygon mesh (immutable: its arrays are read-only views)")
      .def(py::init(&meshFromArrays), py::arg("vertices"), py::arg("faces"), py::arg("sizes") = py::none(),
           py::arg("crease_edges") = py::none(), py::arg("crease_sharpness") = py::none(), py::arg("corners") = py::none(),
           py::arg("corner_sharpness") = py::none(),
           "Mesh(V, F): V (N, 3) float64; F an (M, k) int array, or flat 0-based indices with sizes (M,); crease edges "
           "(E, 2) with their sharpness (E,) and corners (C,) with theirs, as an OBJ's t crease / t corner tags")
      .def_property_readonly("vertices", [](py::object self) {
            const PolyMesh& mesh = *self.cast<const Mesh&>().mesh;
            return readOnlyView(py::dtype::of<double>(), {mesh.vertexCount(), 3}, {sizeof(Point), sizeof(double)},
                                mesh.points.data(), self);
          }, "(N, 3) float64 view")
      .def_property_readonly("faces", &faceArrays, "(indices (sum k,) int32 view, sizes (M,) int32)")
      .def("quads", &quadArray, "all-quad meshes: (M, 4) int32 view of the faces")
      .def_property_readonly("face_offsets", [](py::object self) {
            const PolyMesh& mesh = *self.cast<const Mesh&>().mesh;
            return readOnlyView(py::dtype::of<Index>(), {py::ssize_t(mesh.faceStart.size())}, {sizeof(Index)},
                                mesh.faceStart.data(), self);
          }, "(M + 1,) int32 view: face f is indices[offsets[f]:offsets[f + 1]]")
      .def_property_readonly("tags", &tagsDict, "the OBJ's `t` tags: crease edges and sharpness, corners, holes")
      .def_property_readonly("source", [](const Mesh& self) { return self.source; })
      .def_property_readonly("vertex_count", [](const Mesh& self) { return self.mesh->vertexCount(); })
      .def_property_readonly("face_count", [](const Mesh& self) { return self.mesh->faceCount(); })
      .def("info", [](const Mesh& self) { return toPython(meshInfoValue(self.source, *self.mesh), IntegralNumbers::AsInt); },
           "what `polarview info --json` prints, as a dict")
      .def("save",
           [](const Mesh& self, const py::object& path) {
             // str or os.PathLike, as load() takes it (docs/python.md).
             const py::object name = py::module_::import("os").attr("fspath")(path);
             if (!py::isinstance<py::str>(name)) throw py::type_error("path must be a str or os.PathLike of str");
             saveObj(name.cast<std::string>(), *self.mesh, self.source);
           },
           py::arg("path"), "writes an OBJ atomically, as `polarview refine` does; path: str or os.PathLike")
      .def("__repr__", [](const Mesh& self) {
        return "<polarview.Mesh " + self.source + ": " + std::to_string(self.mesh->vertexCount()) + " vertices, " +
               std::to_string(self.mesh->faceCount()) + " faces>";
      });
  m.def("load", &loadMesh, py::arg("path"), "reads an OBJ file (crease, corner and hole tags included)");
  m.def("refine", &refineMesh, py::arg("mesh"), py::arg("scheme") = "c2ps", py::arg("levels") = 3,
        py::arg("memory_budget") = 0, "the uniform control mesh after `levels` steps, as `polarview refine` writes it");
  m.def("shape", &namedShape, py::arg("name"), py::arg("valence") = py::none(), py::arg("links") = py::none(),
        py::arg("height") = "", "the meshes of `polarview shape` (globe, cap, mushroom, cube, torus, valence20, fingertips)");
}

}  // namespace polarview::python
