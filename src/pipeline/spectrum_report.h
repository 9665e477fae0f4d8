// The spectrum of a scheme's subdivision matrix as one use case: what `polarview spectrum` prints,
// what the Python module's spectrum() returns and what the viewer's Spectrum panel lists, computed
// here once (the paper's Table 1 for RTS; core/subdiv/spectrum.h does the numerics).
#pragma once

#include <string>
#include <vector>

#include "core/subdiv/scheme.h"
#include "core/subdiv/spectrum.h"
#include "pipeline/report_value.h"

namespace polarview {

struct SpectrumRequest {
  Scheme scheme = Scheme::RTS;
  int valence = 5;
  size_t count = 8;      // eigenvalues listed (at most the matrix's size)
  bool vectors = false;  // and their eigenpairs
  bool matrix = false;   // and the matrix itself
  int steps = 8;         // C2PS: the steps measured
};

struct SpectrumReport {
  std::string name;  // the scheme's command-line name
  int valence = 0;
  bool measured = false;  // C2PS: no stationary matrix; `steps` holds Lemma 5 and (30) as measured
  bool polar = false;     // matrix (13) on links 0..5; else Catmull-Clark's 1-ring matrix
  std::vector<C2psScalingStep> steps;  // measured: steps 1..request.steps
  std::vector<TaggedEigenvalue> all;   // every eigenvalue, by decreasing modulus
  size_t shown = 0;                    // the leading ones listed: min(count, all.size())
  std::vector<EigenPair> pairs;        // with `vectors`: the listed ones' eigenpairs
  Matrix matrix;                       // with `matrix`: schemeMatrix
  // The support's order, as the matrix lists it. [O(1)]
  const char* order() const;
};

// C2PS doubles the valence every step: its spectrum is measured on RTS's eigenvectors. [O(1)]
bool spectrumIsMeasured(Scheme scheme);
// The least valence a spectrum of `scheme` takes (RTS's for C2PS, which is measured on RTS). [O(1)]
int spectrumMinValence(Scheme scheme);
// An eigenvalue as reports show it: an imaginary part that is round-off is 0. [O(1)]
Complex shownEigenvalue(const Complex& z);

// The report; the caller has checked the valence (spectrumMinValence..64) and count >= 1. [O(n^2)
// for the eigenvalues, O(count n) more for the vectors; measured: O(steps 6 n 2^steps)]
SpectrumReport makeSpectrumReport(const SpectrumRequest& request);
// A measured report as `spectrum --scheme c2ps --json` prints it. [O(steps)]
ReportValue measuredSpectrumValue(const SpectrumReport& report);

}  // namespace polarview
