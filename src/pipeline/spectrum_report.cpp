// The spectrum use case (see spectrum_report.h).
#include "pipeline/spectrum_report.h"

#include <algorithm>
#include <cmath>

namespace polarview {

const char* SpectrumReport::order() const {
  return polar ? "q_ij at 6 j + i: link i = 0..5 (0: the pole, once per column), column j = 0..n-1 (13)"
               : "v, e_0..e_{n-1} (spoke ends), f_0..f_{n-1} (quad j's far corner, between e_j and e_{j+1})";
}

bool spectrumIsMeasured(Scheme scheme) { return schemeTraits(scheme).polar() && !schemeTraits(scheme).keepsValence; }

int spectrumMinValence(Scheme scheme) { return schemeTraits(spectrumIsMeasured(scheme) ? Scheme::RTS : scheme).minValence; }

Complex shownEigenvalue(const Complex& z) {
  return std::abs(z.imag()) > 1e-12 * std::max(1.0, std::abs(z)) ? z : Complex(z.real(), 0.0);
}

SpectrumReport makeSpectrumReport(const SpectrumRequest& request) {
  SpectrumReport r;
  r.name = schemeName(request.scheme);
  r.valence = request.valence;
  r.measured = spectrumIsMeasured(request.scheme);
  r.polar = schemeTraits(request.scheme).polar();
  if (r.measured) {
    r.steps = c2psEigencoefficientScaling(request.valence, request.steps);
    return r;
  }
  r.all = schemeSpectrum(request.scheme, request.valence);
  r.shown = std::min(r.all.size(), request.count);
  if (request.vectors) r.pairs = schemeEigenPairs(request.scheme, request.valence, r.shown);
  if (request.matrix) r.matrix = schemeMatrix(request.scheme, request.valence);
  return r;
}

ReportValue measuredSpectrumValue(const SpectrumReport& report) {
  ReportBuilder w("spectrum");
  w.beginObject().field("scheme", report.name).field("valence", report.valence).key("steps").beginArray();
  for (const C2psScalingStep& s : report.steps) {
    w.beginObject().field("m", s.m).field("valence", s.valence).field("coefficient_error", s.coefficientError);
    w.field("deviation", s.deviation).field("deviation_links01", s.deviationLinks01).endObject();
  }
  w.endArray().endObject();
  return w.take();
}

}  // namespace polarview
