// The viewer without its window (session.h).
#include "session/session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/subdiv/spectrum.h"
#include "pipeline/model_analysis.h"
#include "pipeline/spectrum_report.h"
#include "pipeline/surface_build.h"
#include "session/settings_rules.h"

namespace polarview {
namespace {

// How many rejected pole candidates of each kind the Poles panel lists (the nearest).
constexpr size_t kRejectedPolesListed = 3;

// Mixes a value into a running hash (to notice when the colour range inputs changed).
void hashMix(uint64_t& h, uint64_t value) { h = (h ^ value) * 1099511628211ull; }

}  // namespace

Session::Session(const SessionOptions& options, WindowServices& window)
    : window_(window),
      document_(options.faceBudget, options.persistRecent),
      surfaces_(options.faceBudget, options.prepareNextLevel) {
  document_.onModelReplaced = [this] {
    surfaces_.modelChanged();
    window_.frameModel();
  };
}

const BuiltSurface* Session::activeSurface() const { return surfaces_.shown(settings_.clampedActiveView()).get(); }

bool Session::apply(DocumentResult result) {
  if (result.notice) notices_.post(std::move(*result.notice));
  if (result.pathField) settings_.file.pathField = std::move(*result.pathField);
  status_.file = document_.fileStatus();
  document_.reportEdit(activeSurface(), settings_, status_.edit);  // a failed save or export shows at once
  return result.ok;
}

std::optional<EditCost> Session::updateModelAndSurfaces() {
  apply(document_.pollLoad());
  apply(document_.pollExport());
  const Model& model = document_.model();
  SurfaceUpdate update = surfaces_.update(surfaceRequest(), model, document_.editor().dragging());
  // A refused or failed request shows what the view shows (the controls tell the truth).
  for (int v = 0; v < kMaxViews; ++v)
    if (const std::optional<SurfaceKey>& shown = update.reverted[size_t(v)]) {
      settings_.views[size_t(v)].scheme = shown->scheme;
      settings_.views[size_t(v)].level = shown->level;
    }
  if (model.mesh)
    for (int v = 0; v < kMaxViews; ++v) surfaces_.report(v, model, status_.views[size_t(v)]);
  return update.editCost;
}

void Session::updatePanels() {
  updatePoleZoom();
  updatePoleInspector();
  updateSpectrum();
  updateMeasures();
  updateColourRange();
  document_.reportEdit(activeSurface(), settings_, status_.edit);
}

bool Session::busy() const {
  return document_.loading() || document_.exporting() ||
         surfaces_.busy(surfaceRequest(), document_.model(), document_.editor().dragging());
}

void Session::updateColourRange() {
  // The curvature map some view shows (views may shade differently: render --shade a,b).
  const std::optional<ShadingParams::Mode> shown = settings_.curvatureShade();
  if (!shown) return;
  const ShadingParams::Mode mode = *shown;
  uint64_t signature = 14695981039346656037ull;
  hashMix(signature, uint64_t(mode));
  hashMix(signature, uint64_t(settings_.colour.quantile * 1e6f));
  // The samples, not the surfaces: a drag makes new surfaces every frame with the same samples.
  for (int v = 0; v < settings_.viewCount; ++v)
    if (surfaces_.shown(v)) hashMix(signature, uint64_t(uintptr_t(surfaces_.shown(v)->samples.get())));
  if (signature != colourRangeSignature_) {
    colourRangeSignature_ = signature;
    collectColourSamples();
  }
  // The histogram follows the range the bar shows (typed or automatic).
  const ColourInterval shownRange = colourInterval(settings_, status_);
  if (shownRange != histogramRange_ || status_.colour.histogram.empty()) {
    histogramRange_ = shownRange;
    status_.colour.histogram = weightedHistogram(colourValues_, colourWeights_, shownRange, kHistogramBins);
  }
}

void Session::collectColourSamples() {
  const ShadingParams::Mode mode = settings_.curvatureShade().value_or(settings_.shading.mode);
  // One range over the samples of every visible view, so equal colours mean equal values.
  // Each view counts by area: weights are normalised per view so a finer level does not outvote.
  std::vector<double>& values = colourValues_;
  std::vector<double>& weights = colourWeights_;
  values.clear();
  weights.clear();
  for (int v = 0; v < settings_.viewCount; ++v) {
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
  status_.colour.sampled = colourStatistics(values, weights, settings_.colour.quantile);
  status_.colour.histogram.clear();  // recomputed for the new samples
}

void Session::updatePoleZoom() {
  // Rings m .. m + 2 need a surface of patch level m + 2 (poleZoomLevel): at level 3 the rings 4..6
  // a zoom asked for did not exist and the views went blank. A new zoom (or ring) raises the views
  // that fall short, or is refused when a view cannot go that deep; a level lowered under a zoom
  // ends the zoom. Views of Catmull-Clark (no polar rings) count only while levels are linked.
  PoleInspectorSettings& inspector = settings_.poleInspector;
  const int m = inspector.zoomRing;
  const bool newZoom = m != poleZoomChecked_;
  poleZoomChecked_ = m;
  if (m < 0) return;
  const int needed = poleZoomLevel(m);
  const std::string rings = "rings " + std::to_string(m) + "-" + std::to_string(m + 2);
  std::vector<int> shortViews;  // views whose level lacks the rings
  for (int v = 0; v < settings_.viewCount; ++v) {
    const View& view = settings_.views[size_t(v)];
    const ViewStatus& status = status_.views[size_t(v)];
    const bool drawnDeeper = status.hasSurface && status.shownLevel == view.level && status.patchLevel >= needed;
    const bool counts = settings_.linkLevels || view.scheme != SchemeChoice::CatmullClark;
    if (!counts || view.level >= needed || drawnDeeper) continue;
    if (!newZoom || needed > status.deepestLevel) {
      inspector.zoomRing = poleZoomChecked_ = -1;
      notices_.post(warning("pole zoom off: " + rings + " need level " + std::to_string(needed) + "; " +
                            (newZoom ? std::string(schemeChoiceLabel(view.scheme)) + " stops at level " +
                                           std::to_string(status.deepestLevel) + " on this model"
                                     : "view " + std::to_string(v + 1) + " shows level " + std::to_string(view.level))));
      return;
    }
    shortViews.push_back(v);
  }
  if (shortViews.empty()) return;
  raiseLevelsForZoom(shortViews, needed);
  notices_.post(info("level " + std::to_string(needed) + " for the pole zoom: " + rings + " are made from level " +
                     std::to_string(m) + " to " + std::to_string(needed)));
}

void Session::raiseLevelsForZoom(const std::vector<int>& shortViews, int needed) {
  if (settings_.linkLevels) {
    for (View& view : settings_.views) view.level = std::max(view.level, needed);
  } else {
    for (int v : shortViews) settings_.views[size_t(v)].level = needed;
  }
}

void Session::startMeasure() {
  if (measureJob_.running()) return;
  const BuiltSurface* shown = activeSurface();
  // Asked before the view shows its surface (`view --do` runs once the model loads): measured when
  // it does (updateMeasures).
  measurePending_ = !shown;
  if (!shown) {
    status_.measures.computing = true;
    return;
  }
  measured_ = std::string(schemeChoiceLabel(shown->key.scheme)) + " level " + std::to_string(shown->key.level);
  status_.measures = {true, {}};
  // The shown patches (the level asked for, caps closed as shown), kept alive by the job, and the
  // model's own tables for whether it is closed.
  const bool closed = meshIsClosed(*model().mesh, model().analysis->topology());
  measureJob_.start([surface = surfaces_.shown(settings_.clampedActiveView()), closed] {
    return measureSurface(surface->patches, closed);
  });
}

void Session::updateMeasures() {
  if (measurePending_ && activeSurface()) startMeasure();
  if (!measureJob_.finished()) return;
  MeasureStatus& shown = status_.measures;
  shown.computing = false;
  try {
    const SurfaceMeasures m = *measureJob_.poll();
    char text[256];
    std::snprintf(text, sizeof text, "%s: area %.10g (± %.1g)", measured_.c_str(), m.area, m.areaError);
    shown.text = text;
    // The solid's centroid where the surface bounds one, else the shell's (`measure` prints both).
    if (m.closed) {
      std::snprintf(text, sizeof text, ", volume %.10g (± %.1g), centroid (%.6g, %.6g, %.6g)", m.volume, m.volumeError,
                    m.centroid.x, m.centroid.y, m.centroid.z);
      shown.text += text;
    } else {
      std::snprintf(text, sizeof text, ", open: no volume; area centroid (%.6g, %.6g, %.6g)", m.areaCentroid.x,
                    m.areaCentroid.y, m.areaCentroid.z);
      shown.text += text;
    }
  } catch (const std::exception& e) {
    shown.text = std::string("could not measure: ") + e.what();
  }
}

void Session::updateSpectrum() {
  SpectrumSettings& spectrum = settings_.spectrum;
  SpectrumStatus& shown = status_.spectrum;
  const bool open = spectrum.open;
  spectrum.open = false;  // the panel marks it again next frame while the section is open
  if (!open || shown.linesValence == spectrum.valence) return;
  // Small (6n x 6n, n <= 24): computed on the GL thread when the valence changes.
  shown.lines.clear();
  try {
    const std::vector<EigenPair> pairs = makeSpectrumReport({Scheme::RTS, spectrum.valence, 8, true}).pairs;
    for (size_t k = 0; k < pairs.size(); ++k) {
      char line[96];
      std::snprintf(line, sizeof line, "v%zu  %.12g  block %d  %s", k, pairs[k].value.real(), pairs[k].alpha,
                    fourierModeName(pairs[k].mode));
      shown.lines.push_back(line);
    }
  } catch (const std::exception& e) {
    shown.lines.push_back(e.what());
  }
  shown.linesValence = spectrum.valence;
  spectrum.k = std::clamp(spectrum.k, 0, std::max(int(shown.lines.size()) - 1, 0));
}

void Session::updatePoleInspector() {
  PoleInspectorSettings& asked = settings_.poleInspector;
  PoleInspectorStatus& inspector = status_.poleInspector;
  const bool open = asked.open;
  asked.open = false;  // the panel marks it again next frame while the section is open
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
  asked.pole = std::clamp(asked.pole, 0, int(inspector.poles.size()) - 1);
  std::vector<SchemeChoice> schemes;
  for (int v = 0; v < settings_.viewCount; ++v)
    if (std::find(schemes.begin(), schemes.end(), settings_.views[size_t(v)].scheme) == schemes.end())
      schemes.push_back(settings_.views[size_t(v)].scheme);
  const Index pole = inspector.poles[size_t(asked.pole)];
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

}  // namespace polarview
