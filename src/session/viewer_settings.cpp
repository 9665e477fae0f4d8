// The settings operations commands and panels share (viewer_settings.h).
#include "session/viewer_settings.h"

namespace polarview {

void setOrthographic(ViewerSettings& settings, bool orthographic) {
  settings.sharedCamera.orthographic = orthographic;
  for (View& view : settings.views) view.camera.orthographic = orthographic;
}

void cycleScheme(ViewerSettings& settings, int view, int step) {
  const int next = (int(settings.views[size_t(view)].scheme) + step + kSchemeChoiceCount) % kSchemeChoiceCount;
  settings.views[size_t(view)].scheme = static_cast<SchemeChoice>(next);
}

}  // namespace polarview
