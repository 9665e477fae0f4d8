// The state operations commands and panels share (viewer_state.h).
#include "session/viewer_state.h"

namespace polarview {

void setAutomaticRange(ViewerState& state, bool automatic) {
  // Turning it off keeps the colours on screen: the typed range starts at the automatic value.
  if (state.colour.automatic && !automatic) {
    state.colour.typedRange = state.colourRange();
    state.colour.typedBelow = state.colourRangeBelow();
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
