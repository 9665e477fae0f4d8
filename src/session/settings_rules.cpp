// The rules that read the settings in the light of the status (settings_rules.h).
#include "session/settings_rules.h"

#include <algorithm>
#include <cstdio>

namespace polarview {

ColourInterval automaticInterval(const ColourRangeSettings& settings, const ColourStatus& status) {
  const ColourStatistics& sampled = status.sampled;
  if (status.oneSign() != 0 || settings.symmetric) return sampled.automaticInterval();
  const double floor = 1e-3 * sampled.symmetricRange;
  return {std::min(sampled.percentiles.low, -floor), std::max(sampled.percentiles.high, floor)};
}

ColourInterval colourInterval(const ViewerSettings& settings, const ViewerStatus& status) {
  const ColourRangeSettings& colour = settings.colour;
  if (colour.automatic) return automaticInterval(colour, status.colour);
  return colour.symmetric ? ColourInterval::symmetric(colour.typedRange) : colour.typedApart;
}

std::string colourRangeNote(const ViewerSettings& settings, const ViewerStatus& status) {
  const ColourInterval range = colourInterval(settings, status);
  if (!range.oneSided()) return {};
  const char* quantity = settings.curvatureShade() == ShadingParams::Mode::Mean ? "H" : "K";
  char text[160];
  if (settings.colour.automatic) {
    const int sign = status.colour.oneSign();
    const bool strict = sign > 0 ? status.colour.sampled.min > 0.0 : status.colour.sampled.max < 0.0;
    std::snprintf(text, sizeof text, "all %s %s 0: range %.3g .. %.3g, one-sided", quantity,
                  sign > 0 ? (strict ? ">" : ">=") : (strict ? "<" : "<="), range.low, range.high);
  } else {
    std::snprintf(text, sizeof text, "range %.3g .. %.3g, one-sided (zero not in it)", range.low, range.high);
  }
  return text;
}

void setAutomaticRange(ViewerSettings& settings, const ViewerStatus& status, bool automatic) {
  // Turning it off keeps the colours on screen: the typed range starts at the automatic value.
  if (settings.colour.automatic && !automatic) {
    const ColourInterval shown = colourInterval(settings, status);
    settings.colour.typedRange = std::max(-shown.low, shown.high);
    settings.colour.typedApart = shown;
  }
  settings.colour.automatic = automatic;
}

void requestLevel(ViewerSettings& settings, const ViewerStatus& status, Notices& notices, int level) {
  // Every view the request applies to must reach the level (ViewStatus::deepestLevel, the session's
  // face-budget estimate); otherwise nothing changes and the notice says how deep it can go.
  for (int v = 0; v < settings.viewCount; ++v) {
    if (!settings.linkLevels && v != settings.activeView) continue;
    const int deepest = status.views[size_t(v)].deepestLevel;
    if (level > deepest || level < 0) {
      notices.post(warning(level < 0 ? "level " + std::to_string(level) + " refused"
                                     : "level " + std::to_string(level) + " refused: " +
                                           schemeChoiceLabel(settings.views[size_t(v)].scheme) + " stops at level " +
                                           std::to_string(deepest) + " on this model"));
      return;
    }
  }
  notices.withdraw("level ");  // an earlier refusal is stale now
  if (settings.linkLevels) {
    for (View& view : settings.views) view.level = level;
  } else {
    settings.views[size_t(settings.activeView)].level = level;
  }
}

}  // namespace polarview
