// The viewer without its window (session.h).
#include "session/session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/subdiv/spectrum.h"
#include "pipeline/model_analysis.h"
#include "pipeline/spectrum_report.h"
#include "pipeline/surface_build.h"

namespace polarview {
namespace {

// How many rejected pole candidates of each kind the Poles panel lists (the nearest).
constexpr size_t kRejectedPolesListed = 3;

// Mixes a value into a running hash (to notice when the colour range inputs changed).
void hashMix(uint64_t& h, uint64_t value) { h = (h ^ value) * 1099511628211ull; }

}  // namespace

Session::Session(const SessionOptions& options, WindowServices& window)
    : window_(window),
      document_(state_, options.faceBudget, options.persistRecent),
      surfaces_(options.faceBudget, options.prepareNextLevel) {
  document_.onModelReplaced = [this] {
    surfaces_.modelChanged(state_);
    window_.frameModel();
  };
}

const BuiltSurface* Session::activeSurface() const {
  return surfaces_.shown(std::clamp(state_.activeView, 0, state_.viewCount - 1)).get();
}

std::optional<EditCost> Session::updateModelAndSurfaces() {
  document_.pollLoad();
  document_.pollExport();
  return surfaces_.update(state_, document_.model(), document_.editor().dragging());
}

void Session::updatePanels() {
  updatePoleZoom();
  updatePoleInspector();
  updateSpectrum();
  updateColourRange();
  document_.updateEditState(activeSurface());
}

bool Session::busy() const {
  return document_.loading() || document_.exporting() ||
         surfaces_.busy(state_, document_.model(), document_.editor().dragging());
}

void Session::updateColourRange() {
  // The curvature map some view shows (views may shade differently: render --shade a,b).
  const std::optional<ShadingParams::Mode> shown = state_.curvatureShade();
  if (!shown) return;
  const ShadingParams::Mode mode = *shown;
  uint64_t signature = 14695981039346656037ull;
  hashMix(signature, uint64_t(mode));
  hashMix(signature, uint64_t(state_.colour.quantile * 1e6f));
  // The samples, not the surfaces: a drag makes new surfaces every frame with the same samples.
  for (int v = 0; v < state_.viewCount; ++v)
    if (surfaces_.shown(v)) hashMix(signature, uint64_t(uintptr_t(surfaces_.shown(v)->samples.get())));
  if (signature != colourRangeSignature_) {
    colourRangeSignature_ = signature;
    collectColourSamples();
  }
  // The histogram follows the range the bar shows (typed or automatic).
  const ColourInterval shownRange = state_.colourInterval();
  if (shownRange != histogramRange_ || state_.colour.histogram.empty()) {
    histogramRange_ = shownRange;
    state_.colour.histogram = weightedHistogram(colourValues_, colourWeights_, shownRange, kHistogramBins);
  }
}

void Session::collectColourSamples() {
  const ShadingParams::Mode mode = state_.curvatureShade().value_or(state_.shading.mode);
  // One range over the samples of every visible view, so equal colours mean equal values.
  // Each view counts by area: weights are normalised per view so a finer level does not outvote.
  std::vector<double>& values = colourValues_;
  std::vector<double>& weights = colourWeights_;
  values.clear();
  weights.clear();
  for (int v = 0; v < state_.viewCount; ++v) {
    if (!surfaces_.shown(v) || !surfaces_.shown(v)->samples) continue;
    const CurvatureSamples& s = *surfaces_.shown(v)->samples;
    const std::vector<double>& samples = mode == ShadingParams::Mode::Gaussian ? s.gaussian : s.mean;
    double area = 0.0;
    for (double a : s.areas) area += a;
    if (!(area > 0.0)) continue;
    values.insert(values.end(), samples.begin(), samples.end());
    for (double a : s.areas) weights.push_back(a / area);
  }
  if (values.empty()) return;
  ColourRangeSettings& colour = state_.colour;
  colour.sampled = colourStatistics(values, weights, colour.quantile);
  colour.histogram.clear();  // recomputed for the new samples
}

void Session::updatePoleZoom() {
  // Rings m .. m + 2 need a surface of patch level m + 2 (poleZoomLevel): at level 3 the rings 4..6
  // a zoom asked for did not exist and the views went blank. A new zoom (or ring) raises the views
  // that fall short, or is refused when a view cannot go that deep; a level lowered under a zoom
  // ends the zoom. Views of Catmull-Clark (no polar rings) count only while levels are linked.
  PoleInspectorSettings& inspector = state_.poleInspector;
  const int m = inspector.zoomRing;
  const bool newZoom = m != poleZoomChecked_;
  poleZoomChecked_ = m;
  if (m < 0) return;
  const int needed = poleZoomLevel(m);
  const std::string rings = "rings " + std::to_string(m) + "-" + std::to_string(m + 2);
  std::vector<int> short_;  // views whose level lacks the rings
  for (int v = 0; v < state_.viewCount; ++v) {
    const View& view = state_.views[size_t(v)];
    const ViewStatus& status = view.status;
    const bool drawnDeeper = status.hasSurface && status.shownLevel == view.level && status.patchLevel >= needed;
    const bool counts = state_.linkLevels || view.scheme != SchemeChoice::CatmullClark;
    if (!counts || view.level >= needed || drawnDeeper) continue;
    if (!newZoom || needed > status.deepestLevel) {
      inspector.zoomRing = poleZoomChecked_ = -1;
      state_.notice = "pole zoom off: " + rings + " need level " + std::to_string(needed) + "; " +
                      (newZoom ? std::string(schemeChoiceLabel(view.scheme)) + " stops at level " +
                                     std::to_string(status.deepestLevel) + " on this model"
                               : "view " + std::to_string(v + 1) + " shows level " + std::to_string(view.level));
      return;
    }
    short_.push_back(v);
  }
  if (short_.empty()) return;
  if (state_.linkLevels) {
    for (View& view : state_.views) view.level = std::max(view.level, needed);
  } else {
    for (int v : short_) state_.views[size_t(v)].level = needed;
  }
  state_.notice = "level " + std::to_string(needed) + " for the pole zoom: " + rings + " are made from level " +
                  std::to_string(m) + " to " + std::to_string(needed);
}

void Session::updateSpectrum() {
  SpectrumSettings& spectrum = state_.spectrum;
  const bool open = spectrum.open;
  spectrum.open = false;  // the panel marks it again next frame while the section is open
  if (!open || spectrum.linesValence == spectrum.valence) return;
  // Small (6n x 6n, n <= 24): computed on the GL thread when the valence changes.
  spectrum.lines.clear();
  try {
    const std::vector<EigenPair> pairs = makeSpectrumReport({Scheme::RTS, spectrum.valence, 8, true}).pairs;
    for (size_t k = 0; k < pairs.size(); ++k) {
      char line[96];
      std::snprintf(line, sizeof line, "v%zu  %.12g  block %d  %s", k, pairs[k].value.real(), pairs[k].alpha,
                    fourierModeName(pairs[k].mode));
      spectrum.lines.push_back(line);
    }
  } catch (const std::exception& e) {
    spectrum.lines.push_back(e.what());
  }
  spectrum.linesValence = spectrum.valence;
  spectrum.k = std::clamp(spectrum.k, 0, std::max(int(spectrum.lines.size()) - 1, 0));
}

void Session::updatePoleInspector() {
  PoleInspectorSettings& inspector = state_.poleInspector;
  const bool open = inspector.open;
  inspector.open = false;  // the panel marks it again next frame while the section is open
  if (!document_.model().mesh) return;
  if (inspectPolesOf_ != document_.model().generation) {
    inspectPolesOf_ = document_.model().generation;
    try {
      inspector.survey = surveyPoles(*document_.model().mesh, document_.model().analysis->polarConfigs(),
                                     kRejectedPolesListed);
    } catch (const std::exception&) {
      inspector.survey = {};
    }
    inspector.poles = inspector.survey.poles;
    inspector.inspections.clear();
    inspectShown_.clear();
  }
  // A finished job: shown if it is still what the panel asks for.
  if (inspectJob_.finished()) {
    try {
      inspector.inspections = std::move(*inspectJob_.poll());
      inspector.error.clear();
    } catch (const std::exception& e) {
      inspector.inspections.clear();
      inspector.error = e.what();
    }
    inspectShown_ = inspectRunning_;
  }
  inspector.computing = inspectJob_.running();
  if (!open || inspector.poles.empty() || inspectJob_.running()) return;
  // The selected pole under each scheme the visible views show (once each, in view order).
  inspector.pole = std::clamp(inspector.pole, 0, int(inspector.poles.size()) - 1);
  std::vector<SchemeChoice> schemes;
  for (int v = 0; v < state_.viewCount; ++v)
    if (std::find(schemes.begin(), schemes.end(), state_.views[size_t(v)].scheme) == schemes.end())
      schemes.push_back(state_.views[size_t(v)].scheme);
  const Index pole = inspector.poles[size_t(inspector.pole)];
  std::string key = std::to_string(document_.model().generation) + ":" + std::to_string(document_.model().points) + ":" + std::to_string(pole);
  for (SchemeChoice scheme : schemes) key += ":" + std::string(schemeChoiceCliName(scheme));
  if (key == inspectShown_) return;
  inspectRunning_ = key;
  inspector.computing = true;
  inspectJob_.start([mesh = document_.model().mesh, pole, schemes] {
    std::vector<PoleInspection> out;
    // Rings deep enough to see the trend: C2PS to ring 10 (valence x 1024), RTS and BPS to 14
    // (they keep n columns), Catmull-Clark to level 8.
    for (SchemeChoice scheme : schemes) {
      const Scheme refined = refineOptionsFor(scheme, 0).scheme;
      const int rings = refined == Scheme::CatmullClark ? 8 : schemeTraits(refined).keepsValence ? 14 : 10;
      out.push_back(inspectPole(*mesh, pole, scheme, rings));
    }
    return out;
  });
}

void Session::expireNotice() {
  const auto now = std::chrono::steady_clock::now();
  if (state_.notice != shownNotice_) {
    shownNotice_ = state_.notice;
    noticeSince_ = now;
  } else if (!state_.notice.empty() && now - noticeSince_ > kNoticeLifetime) {
    state_.notice.clear();
    shownNotice_.clear();
  }
}

}  // namespace polarview
