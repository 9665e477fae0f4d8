// The analysis: pole() (`polarview pole --json`), spectrum() (`polarview spectrum`, the paper's
// Table 1), subdivision_matrix() (one step as a scipy.sparse matrix) and measure() (`polarview
// measure`).
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include "core/subdiv/refiner.h"
#include "pipeline/memory_budget.h"
#include "pipeline/model.h"
#include "pipeline/patch_export.h"
#include "pipeline/pole_report.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/spectrum_report.h"
#include "pipeline/surface_measures.h"
#include "python/bindings.h"

namespace polarview::python {

namespace {

bool polarChoice(SchemeChoice c) { return schemeTraits(schemeChoiceVariant(c).scheme).polar(); }

py::list poleAnalysis(const Mesh& m, const std::string& scheme, int rings) {
  const SchemeVariant variant = schemeArgument(scheme);
  if (!schemeTraits(variant.scheme).polar())
    throw py::value_error("pole analysis needs a polar scheme (" + schemeChoiceNames(", ", polarChoice) + ")");
  if (rings < 0 || rings > 20) throw py::value_error("rings must be in 0..20");
  return toPython(makePoleReport(*m.mesh, m.source, variant, rings).value["poles"], IntegralNumbers::AsInt);
}

// Complex vectors as rows of a (count, size) array; NaN rows where a pair has none (zero or
// defective eigenvalues).
py::array_t<std::complex<double>> vectorRows(const std::vector<EigenPair>& pairs, std::vector<Complex> EigenPair::*member) {
  size_t size = 0;
  for (const EigenPair& p : pairs) size = std::max(size, (p.*member).size());
  py::array_t<std::complex<double>> out({py::ssize_t(pairs.size()), py::ssize_t(size)});
  for (size_t k = 0; k < pairs.size(); ++k)
    for (size_t i = 0; i < size; ++i)
      out.mutable_at(k, i) = (pairs[k].*member).empty() ? Complex(std::nan(""), std::nan("")) : (pairs[k].*member)[i];
  return out;
}

// The eigenvalues (round-off imaginary parts 0, as `spectrum` prints them), their Fourier blocks and
// modes, eigenvectors and the matrix of a report made with vectors and matrix.
py::dict eigenDict(const SpectrumReport& r) {
  py::array_t<std::complex<double>> values(static_cast<py::ssize_t>(r.shown));
  py::array_t<int> blocks(static_cast<py::ssize_t>(r.shown));
  py::list modes;
  for (size_t k = 0; k < r.shown; ++k) {
    values.mutable_at(k) = shownEigenvalue(r.all[k].value), blocks.mutable_at(k) = r.all[k].alpha;
    modes.append(fourierModeName(r.pairs[k].mode));
  }
  py::array_t<double> dense({py::ssize_t(r.matrix.size()), py::ssize_t(r.matrix.empty() ? 0 : r.matrix[0].size())});
  for (size_t i = 0; i < r.matrix.size(); ++i)
    for (size_t j = 0; j < r.matrix[i].size(); ++j) dense.mutable_at(i, j) = r.matrix[i][j];
  py::dict d;
  d["scheme"] = r.name, d["valence"] = r.valence, d["size"] = r.all.size();
  d["eigenvalues"] = values, d["fourier_blocks"] = blocks, d["modes"] = modes;
  d["right"] = vectorRows(r.pairs, &EigenPair::right), d["left"] = vectorRows(r.pairs, &EigenPair::left);
  d["right_profile"] = vectorRows(r.pairs, &EigenPair::rightProfile);
  d["left_profile"] = vectorRows(r.pairs, &EigenPair::leftProfile);
  d["matrix"] = dense;
  return d;
}

// C2PS: no stationary matrix; Lemma 5 and (30) measured on RTS's eigenvectors, as `spectrum --scheme
// c2ps --json` prints them.
py::object spectrum(const std::string& scheme, int valence, int count, int steps) {
  const SchemeVariant variant = schemeArgument(scheme);
  if (variant.uniformFirstStep) throw py::value_error("the Section-6 first step has no subdivision matrix of its own");
  const int least = std::max(3, spectrumMinValence(variant.scheme));
  if (valence < least || valence > 64)
    throw py::value_error(std::string(schemeName(variant.scheme)) + " takes valence " + std::to_string(least) + "..64");
  const bool measured = spectrumIsMeasured(variant.scheme);
  if (!measured && count < 1) throw py::value_error("count must be at least 1");
  if (measured && (steps < 1 || steps > 12)) throw py::value_error("steps must be in 1..12");
  const SpectrumReport r = makeSpectrumReport({variant.scheme, valence, size_t(std::max(count, 1)), true, true, steps});
  if (measured) return toPython(measuredSpectrumValue(r), IntegralNumbers::AsFloat);
  return eigenDict(r);
}

// The matrix applied to the mesh's points must give the step's points (to round-off of the sums'
// order): a rule that is not linear, or a column read wrong, fails here instead of handing out a
// wrong matrix.
void checkAgainstStep(py::object matrix, const PolyMesh& mesh, const std::vector<Point>& step) {
  py::array_t<double> points({static_cast<py::ssize_t>(mesh.points.size()), py::ssize_t(3)});
  double size = 1.0;
  for (size_t i = 0; i < mesh.points.size(); ++i)
    for (int c = 0; c < 3; ++c) points.mutable_at(i, c) = mesh.points[i][c], size = std::max(size, std::abs(mesh.points[i][c]));
  const py::array_t<double> image = matrix.attr("__matmul__")(points);
  double worst = 0.0;
  for (size_t i = 0; i < step.size(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(image.at(i, c) - step[i][c]));
  if (!(worst <= 1e-9 * size))
    throw std::runtime_error("subdivision_matrix: the matrix misses the step by " + std::to_string(worst));
}

// One refinement step as a sparse matrix (rows: the new points, columns: the old). The rules have
// no stencil tables (the polar rules are O(n) Fourier sums), but a step is linear in the points:
// column j is the step applied to the unit vector e_j. Each pass carries three columns, one per
// coordinate. The result is checked against the step applied to the mesh's own points.
py::array_t<double> vectorArray(const Point& p) { return py::array_t<double>(3, &p.x); }
py::array_t<double> tensorArray(const glm::dmat3& t) {
  py::array_t<double> out({3, 3});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.mutable_at(i, j) = t[j][i];
  return out;
}

// `polarview measure --json` as a dict, centroids (3,) and inertia tensors (3, 3) as arrays; the
// solid's entries are None for an open surface.
py::dict measure(const Mesh& m, const std::string& scheme, int level, int points, size_t memoryBudget) {
  if (level < 0 || level > 64) throw py::value_error("level must be in 0..64");
  if (points < 2 || points > 16) throw py::value_error("points must be in 2..16");
  const SchemeVariant variant = schemeArgument(scheme);
  requireCurvatureExtent(*m.mesh, m.source);
  const RefineRequest request = RefineRequest::withinMemory({variant.scheme, level, variant.uniformFirstStep},
                                                            RefinePath::FeatureAdaptive, memoryBudget);
  SurfaceMeasures r;
  {
    py::gil_scoped_release unlocked;
    r = measureSurface(makePatchSet(*m.mesh, m.source, request).patches, meshIsClosed(*m.mesh), points);
  }
  py::dict d;
  d["scheme"] = schemeVariantName(variant), d["level"] = level, d["patches"] = r.patches, d["points"] = r.points;
  d["closed"] = r.closed, d["area"] = r.area, d["area_error"] = r.areaError;
  d["area_centroid"] = vectorArray(r.areaCentroid), d["shell_inertia"] = tensorArray(r.shellInertia);
  const py::object none = py::none();
  d["volume"] = r.closed ? py::object(py::float_(r.volume)) : none;
  d["volume_error"] = r.closed ? py::object(py::float_(r.volumeError)) : none;
  d["centroid"] = r.closed ? py::object(vectorArray(r.centroid)) : none;
  d["inertia"] = r.closed ? py::object(tensorArray(r.inertia)) : none;
  return d;
}

py::object subdivisionMatrix(const Mesh& m, const std::string& scheme) {
  const SchemeVariant variant = schemeArgument(scheme);
  const RefineOptions options{variant.scheme, 1, variant.uniformFirstStep};
  const size_t maxFaces = checkMemoryBudget(*m.mesh, options, m.source, 0);
  std::vector<int64_t> rows, columns;
  std::vector<double> values;
  size_t rowCount = 0;
  std::vector<Point> reference;
  {
    py::gil_scoped_release unlocked;
    Refinement refinement(*m.mesh, options, m.source, maxFaces);
    // A non-manifold input was refined split: rows are the merged points `refine` writes.
    auto stepPoints = [&refinement] {
      return refinement.splitInput() ? refinement.outputMesh().points : refinement.finest().mesh.points;
    };
    reference = stepPoints();
    rowCount = reference.size();
    const size_t n = m.mesh->points.size();
    std::vector<Point> unit(n, Point(0.0));
    for (size_t first = 0; first < n; first += 3) {
      for (size_t c = 0; c < 3 && first + c < n; ++c) unit[first + c][int(c)] = 1.0;
      refinement.updatePositions(unit);
      const std::vector<Point> image = stepPoints();
      for (size_t i = 0; i < image.size(); ++i)
        for (size_t c = 0; c < 3 && first + c < n; ++c)
          if (image[i][int(c)] != 0.0) rows.push_back(int64_t(i)), columns.push_back(int64_t(first + c)), values.push_back(image[i][int(c)]);
      for (size_t c = 0; c < 3 && first + c < n; ++c) unit[first + c] = Point(0.0);
    }
  }
  py::object sparse = py::module_::import("scipy.sparse");
  py::array_t<double> data(static_cast<py::ssize_t>(values.size()), values.data());
  py::array_t<int64_t> rowIds(static_cast<py::ssize_t>(rows.size()), rows.data());
  py::array_t<int64_t> columnIds(static_cast<py::ssize_t>(columns.size()), columns.data());
  py::object matrix = sparse.attr("coo_matrix")(py::make_tuple(data, py::make_tuple(rowIds, columnIds)),
                                                py::make_tuple(rowCount, m.mesh->points.size())).attr("tocsr")();
  checkAgainstStep(matrix, *m.mesh, reference);
  return matrix;
}

}  // namespace

void bindAnalysis(py::module_& m) {
  m.def("pole", &poleAnalysis, py::arg("mesh"), py::arg("scheme") = "c2ps", py::arg("rings") = 0,
        "per refinable pole, what `polarview pole --json --rings M` prints: limit, normal, K, H, p0..p5, rings");
  m.def("spectrum", &spectrum, py::arg("scheme"), py::arg("valence"), py::arg("count") = 8, py::arg("steps") = 8,
        "the leading eigenvalues with their eigenvectors and the matrix, as `polarview spectrum --vectors`; "
        "c2ps: Lemma 5 measured over `steps` steps");
  m.def("measure", &measure, py::arg("mesh"), py::arg("scheme") = "c2ps", py::arg("level") = 3, py::arg("points") = 8,
        py::arg("memory_budget") = 0, "area, enclosed volume, centroid and inertia of the limit surface");
  m.def("subdivision_matrix", &subdivisionMatrix, py::arg("mesh"), py::arg("scheme") = "c2ps",
        "one refinement step as a scipy.sparse.csr_matrix: rows the new points (as refine(mesh, scheme, 1) "
        "lists them), columns the mesh's vertices");
}

}  // namespace polarview::python
