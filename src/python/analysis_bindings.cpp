// The analysis: pole() (`polarview pole --json`), spectrum() (`polarview spectrum`, the paper's
// Table 1) and subdivision_matrix() (one step as a scipy.sparse matrix).
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include "core/subdiv/refiner.h"
#include "core/subdiv/spectrum.h"
#include "pipeline/memory_budget.h"
#include "pipeline/pole_report.h"
#include "python/bindings.h"

namespace polarview::python {

namespace {

py::list poleAnalysis(const Mesh& m, const std::string& scheme, int rings) {
  const SchemeVariant variant = schemeArgument(scheme);
  if (!schemeTraits(variant.scheme).polar()) throw py::value_error("pole analysis needs a polar scheme (c2ps, c2ps-u, rts, rts-u, bps)");
  if (rings < 0 || rings > 20) throw py::value_error("rings must be in 0..20");
  return parseJson(makePoleReport(*m.mesh, m.source, variant, rings).json)["poles"];
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

// C2PS: no stationary matrix; Lemma 5 and (30) measured on RTS's eigenvectors, as `spectrum --scheme c2ps`.
py::dict c2psSpectrum(int valence, int steps) {
  py::list rows;
  for (const C2psScalingStep& s : c2psEigencoefficientScaling(valence, steps)) {
    py::dict row;
    row["m"] = s.m, row["valence"] = s.valence, row["coefficient_error"] = s.coefficientError;
    row["deviation"] = s.deviation, row["deviation_links01"] = s.deviationLinks01;
    rows.append(row);
  }
  py::dict d;
  d["scheme"] = "c2ps", d["valence"] = valence, d["steps"] = rows;
  return d;
}

py::dict spectrum(const std::string& scheme, int valence, int count, int steps) {
  const SchemeVariant variant = schemeArgument(scheme);
  const SchemeTraits& traits = schemeTraits(variant.scheme);
  if (variant.uniformFirstStep) throw py::value_error("the Section-6 first step has no subdivision matrix of its own");
  const bool c2ps = traits.polar() && !traits.keepsValence;
  const SchemeTraits& bounded = schemeTraits(c2ps ? Scheme::RTS : variant.scheme);  // C2PS: measured on RTS's vectors
  if (valence < std::max(3, bounded.minValence) || valence > 64)
    throw py::value_error(std::string(traits.name) + " takes valence " + std::to_string(std::max(3, bounded.minValence)) + "..64");
  if (c2ps) return c2psSpectrum(valence, steps);
  if (count < 1) throw py::value_error("count must be at least 1");
  const std::vector<TaggedEigenvalue> all = schemeSpectrum(variant.scheme, valence);
  const size_t shown = std::min(all.size(), size_t(count));
  const std::vector<EigenPair> pairs = schemeEigenPairs(variant.scheme, valence, shown);
  py::array_t<std::complex<double>> values(static_cast<py::ssize_t>(shown));
  py::array_t<int> blocks(static_cast<py::ssize_t>(shown));
  py::list modes;
  for (size_t k = 0; k < shown; ++k) {
    // An imaginary part that is round-off is 0, as `spectrum` prints it.
    const Complex z = all[k].value;
    const bool real = std::abs(z.imag()) <= 1e-12 * std::max(1.0, std::abs(z));
    values.mutable_at(k) = real ? Complex(z.real(), 0.0) : z, blocks.mutable_at(k) = all[k].alpha;
    modes.append(fourierModeName(pairs[k].mode));
  }
  const Matrix matrix = schemeMatrix(variant.scheme, valence);
  py::array_t<double> dense({py::ssize_t(matrix.size()), py::ssize_t(matrix.empty() ? 0 : matrix[0].size())});
  for (size_t i = 0; i < matrix.size(); ++i)
    for (size_t j = 0; j < matrix[i].size(); ++j) dense.mutable_at(i, j) = matrix[i][j];
  py::dict d;
  d["scheme"] = traits.name, d["valence"] = valence, d["size"] = all.size();
  d["eigenvalues"] = values, d["fourier_blocks"] = blocks, d["modes"] = modes;
  d["right"] = vectorRows(pairs, &EigenPair::right), d["left"] = vectorRows(pairs, &EigenPair::left);
  d["right_profile"] = vectorRows(pairs, &EigenPair::rightProfile);
  d["left_profile"] = vectorRows(pairs, &EigenPair::leftProfile);
  d["matrix"] = dense;
  return d;
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
  m.def("subdivision_matrix", &subdivisionMatrix, py::arg("mesh"), py::arg("scheme") = "c2ps",
        "one refinement step as a scipy.sparse.csr_matrix: rows the new points (as refine(mesh, scheme, 1) "
        "lists them), columns the mesh's vertices");
}

}  // namespace polarview::python
