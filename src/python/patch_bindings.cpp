// Limit patches: limit_patches() (the feature-adaptive patches `polarview export` writes), their
// arrays (strided read-only views into the patches), bezier(), and evaluate() vectorised.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "core/spline/bezierview_export.h"
#include "pipeline/memory_budget.h"
#include "pipeline/patch_export.h"
#include "python/bindings.h"

namespace polarview::python {

namespace {

// The patches as made (positions relative to their frames' origins, for evaluate's precision at
// depth) and in absolute coordinates (the arrays' views).
struct Patches {
  PatchSet set;
  std::vector<Patch> absolute;
  int level = 0;
  std::string scheme;
};

Patches limitPatches(const Mesh& m, const std::string& scheme, int level, bool uniform, size_t memoryBudget) {
  if (level < 0 || level > 64) throw py::value_error("level must be in 0..64");
  const SchemeVariant variant = schemeArgument(scheme);
  const RefineOptions options{variant.scheme, level, variant.uniformFirstStep};
  const RefineRequest request =  // as `export`
      RefineRequest::withinMemory(options, uniform ? RefinePath::Uniform : RefinePath::FeatureAdaptive, memoryBudget);
  py::gil_scoped_release unlocked;
  Patches p{makePatchSet(*m.mesh, m.source, request), {}, level, schemeVariantName(variant)};
  p.absolute.reserve(p.set.patches.size());
  for (const Patch& patch : p.set.patches) p.absolute.push_back(withAbsolutePositions(patch));
  return p;
}

// A per-patch field as a strided view: `offset` bytes into each Patch, `shape` after the patch axis.
py::array fieldView(py::object self, py::dtype dtype, size_t offset, std::vector<py::ssize_t> shape,
                    std::vector<py::ssize_t> strides) {
  const Patches& p = self.cast<const Patches&>();
  shape.insert(shape.begin(), py::ssize_t(p.absolute.size()));
  strides.insert(strides.begin(), py::ssize_t(sizeof(Patch)));
  const char* base = reinterpret_cast<const char*>(p.absolute.data());
  return readOnlyView(std::move(dtype), shape, strides, p.absolute.empty() ? nullptr : base + offset, self);
}

// (P, 4, 4, 3) Bezier points by bicubicBezier, [p, j, i] as control_points; PoleCaps (not bicubic) NaN.
py::array_t<double> bezierPoints(const Patches& p) {
  py::array_t<double> out({py::ssize_t(p.absolute.size()), py::ssize_t(4), py::ssize_t(4), py::ssize_t(3)});
  double* x = out.mutable_data();
  for (const Patch& patch : p.absolute) {
    if (patch.kind == PatchKind::PoleCap) {
      std::fill(x, x + 48, std::nan(""));
    } else {
      // BezierPatch lists cp[4 i + j] (i along u); the array is [j, i] as control_points.
      const BezierPatch bezier = bicubicBezier(patch);
      for (size_t i = 0; i < 4; ++i)
        for (size_t j = 0; j < 4; ++j)
          for (int c = 0; c < 3; ++c) x[3 * (4 * j + i) + size_t(c)] = bezier.cp[4 * i + j][c];
    }
    x += 48;
  }
  return out;
}

// What evaluate() returns for Q parameters: arrays of length Q.
struct Evaluation {
  py::array_t<double> position, normal, du, dv, gaussian, mean, k1, k2;
  explicit Evaluation(py::ssize_t q)
      : position({q, py::ssize_t(3)}), normal({q, py::ssize_t(3)}), du({q, py::ssize_t(3)}), dv({q, py::ssize_t(3)}),
        gaussian(q), mean(q), k1(q), k2(q) {}
  void store(py::ssize_t i, const SurfacePoint& s) {
    for (int c = 0; c < 3; ++c) {
      position.mutable_at(i, c) = s.position[c], normal.mutable_at(i, c) = s.normal[c];
      du.mutable_at(i, c) = s.du[c], dv.mutable_at(i, c) = s.dv[c];
    }
    // Principal curvatures from K and H: H +- sqrt(H^2 - K) (round-off below 0 clamped).
    const double root = std::sqrt(std::max(0.0, s.mean * s.mean - s.gaussian));
    gaussian.mutable_at(i) = s.gaussian, mean.mutable_at(i) = s.mean;
    k1.mutable_at(i) = s.mean + root, k2.mutable_at(i) = s.mean - root;
  }
  py::dict dict() const {
    py::dict d;
    d["position"] = position, d["normal"] = normal, d["du"] = du, d["dv"] = dv;
    d["gaussian"] = gaussian, d["mean"] = mean, d["k1"] = k1, d["k2"] = k2;
    return d;
  }
};

py::dict evaluate(const Patches& p, const py::array_t<int64_t, py::array::c_style | py::array::forcecast>& ids,
                  const py::array_t<double, py::array::c_style | py::array::forcecast>& uv) {
  if (ids.ndim() != 1 || uv.ndim() != 2 || uv.shape(1) != 2 || uv.shape(0) != ids.shape(0))
    throw py::value_error("evaluate expects patch_ids (Q,) and uv (Q, 2)");
  const py::ssize_t q = ids.shape(0);
  for (py::ssize_t i = 0; i < q; ++i) {
    if (ids.at(i) < 0 || size_t(ids.at(i)) >= p.set.patches.size())
      throw py::value_error("patch id " + std::to_string(ids.at(i)) + " out of range (" +
                            std::to_string(p.set.patches.size()) + " patches)");
    if (!(uv.at(i, 0) >= 0.0 && uv.at(i, 0) <= 1.0 && uv.at(i, 1) >= 0.0 && uv.at(i, 1) <= 1.0))
      throw py::value_error("uv[" + std::to_string(i) + "] outside [0, 1]^2");
  }
  Evaluation out(q);
  for (py::ssize_t i = 0; i < q; ++i) out.store(i, evaluatePatch(p.set.patches[size_t(ids.at(i))], uv.at(i, 0), uv.at(i, 1)));
  return out.dict();
}

py::list kindNames() {
  py::list names;
  for (int k = 0; k <= int(PatchKind::EndCap); ++k) names.append(patchKindName(PatchKind(k)));
  return names;
}

}  // namespace

void bindPatches(py::module_& m) {
  const py::dtype f64 = py::dtype::of<double>(), i32 = py::dtype::of<int32_t>();
  py::class_<Patches>(m, "Patches",
                      "Limit patches (src/core/spline/patch.h): uniform bicubic B-spline control points per patch, "
                      "PoleCaps in their raw 16-slot layout")
      .def("__len__", [](const Patches& p) { return p.absolute.size(); })
      .def_property_readonly("control_points", [f64](py::object self) {
            return fieldView(self, f64, offsetof(Patch, cp), {4, 4, 3}, {4 * sizeof(Point), sizeof(Point), sizeof(double)});
          }, "(P, 4, 4, 3) float64 view: [p, j, i] = cp[4 j + i] (i along u, j along v), absolute coordinates")
      .def_property_readonly("kind", [](py::object self) {
            return fieldView(self, py::dtype::of<uint8_t>(), offsetof(Patch, kind), {}, {});
          }, "(P,) uint8 view: index into kind_names")
      .def_property_readonly("level", [](py::object self) {
            return fieldView(self, py::dtype::of<uint8_t>(), offsetof(Patch, level), {}, {});
          }, "(P,) uint8 view: the refinement level the patch was extracted at")
      .def_property_readonly("ring", [i32](py::object self) { return fieldView(self, i32, offsetof(Patch, ring), {}, {}); },
                             "(P,) int32 view: polar ring m (PolarRing, PoleCap), else -1")
      .def_property_readonly("pole", [i32](py::object self) { return fieldView(self, i32, offsetof(Patch, pole), {}, {}); },
                             "(P,) int32 view: the pole's index, else -1")
      .def_property_readonly("face", [i32](py::object self) { return fieldView(self, i32, offsetof(Patch, face), {}, {}); },
                             "(P,) int32 view: the face at `level` the patch was made from (-1 for caps)")
      .def_property_readonly("edge_level_delta", [](py::object self) {
            return fieldView(self, py::dtype::of<int8_t>(), offsetof(Patch, edgeLevelDelta), {4}, {1});
          }, "(P, 4) int8 view: level jump across each edge (patch.h)")
      .def_property_readonly_static("kind_names", [](py::object) { return kindNames(); })
      .def_property_readonly("scheme", [](const Patches& p) { return p.scheme; })
      .def_property_readonly("max_level", [](const Patches& p) { return p.level; })
      .def("counts", [](const Patches& p) {
            py::dict d;
            for (int k = 0; k <= int(PatchKind::EndCap); ++k) d[patchKindName(PatchKind(k))] = p.set.count(PatchKind(k));
            return d;
          }, "patches per kind")
      .def("bezier", &bezierPoints, "(P, 4, 4, 3) float64: the exact bicubic Bezier points, [p, j, i] as control_points; NaN for PoleCaps");
  m.def("limit_patches", &limitPatches, py::arg("mesh"), py::arg("scheme") = "c2ps", py::arg("level") = 3,
        py::arg("uniform") = false, py::arg("memory_budget") = 0,
        "the limit surface's patches after `level` levels, as `polarview export` makes them");
  m.def("evaluate", &evaluate, py::arg("patches"), py::arg("patch_ids"), py::arg("uv"),
        "position, normal, du, dv (Q, 3) and gaussian, mean, k1, k2 (Q,) at uv (Q, 2) of patches patch_ids (Q,)");
}

}  // namespace polarview::python
