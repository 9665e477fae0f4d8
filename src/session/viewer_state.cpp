// The state operations commands and panels share (viewer_state.h).
#include "session/viewer_state.h"

#include <algorithm>
#include <cstdio>

namespace polarview {

ColourInterval ColourRangeSettings::automaticInterval() const {
  if (oneSign() != 0 || symmetric) return sampled.automaticInterval();
  const double floor = 1e-3 * sampled.symmetricRange;
  return {std::min(sampled.percentiles.low, -floor), std::max(sampled.percentiles.high, floor)};
}

std::string colourRangeNote(const ViewerState& state) {
  const ColourInterval range = state.colourInterval();
  if (!range.oneSided()) return {};
  const char* quantity = state.curvatureShade() == ShadingParams::Mode::Mean ? "H" : "K";
  char text[160];
  if (state.colour.automatic) {
    const int sign = state.colour.oneSign();
    const bool strict = sign > 0 ? state.colour.sampled.min > 0.0 : state.colour.sampled.max < 0.0;
    std::snprintf(text, sizeof text, "all %s %s 0: range %.3g .. %.3g, one-sided", quantity,
                  sign > 0 ? (strict ? ">" : ">=") : (strict ? "<" : "<="), range.low, range.high);
  } else {
    std::snprintf(text, sizeof text, "range %.3g .. %.3g, one-sided (zero not in it)", range.low, range.high);
  }
  return text;
}

void setAutomaticRange(ViewerState& state, bool automatic) {
  // Turning it off keeps the colours on screen: the typed range starts at the automatic value.
  if (state.colour.automatic && !automatic) {
    const ColourInterval shown = state.colourInterval();
    state.colour.typedRange = std::max(-shown.low, shown.high);
    state.colour.typedApart = shown;
  }
  state.colour.automatic = automatic;
}

void requestLevel(ViewerState& state, int level) {
  // Every view the request applies to must reach the level (ViewStatus::deepestLevel, the app's
  // face-budget estimate); otherwise nothing changes and the notice says how deep it can go.
  for (int v = 0; v < state.viewCount; ++v) {
    if (!state.linkLevels && v != state.activeView) continue;
    const ViewStatus& status = state.views[size_t(v)].status;
    if (level > status.deepestLevel || level < 0) {
      state.notice = level < 0 ? "level " + std::to_string(level) + " refused"
                               : "level " + std::to_string(level) + " refused: " +
                                     schemeChoiceLabel(state.views[size_t(v)].scheme) + " stops at level " +
                                     std::to_string(status.deepestLevel) + " on this model";
      return;
    }
  }
  if (state.notice.rfind("level ", 0) == 0) state.notice.clear();  // an earlier refusal is stale now
  if (state.linkLevels) {
    for (View& view : state.views) view.level = level;
  } else {
    state.views[size_t(state.activeView)].level = level;
  }
}

void setOrthographic(ViewerState& state, bool orthographic) {
  state.sharedCamera.orthographic = orthographic;
  for (View& view : state.views) view.camera.orthographic = orthographic;
}

void cycleScheme(ViewerState& state, int view, int step) {
  int next = (int(state.views[view].scheme) + step + kSchemeChoiceCount) % kSchemeChoiceCount;
  state.views[view].scheme = static_cast<SchemeChoice>(next);
}

}  // namespace polarview
