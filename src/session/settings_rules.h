// The rules that read the settings in the light of the status: the colour range the views use now
// (automatic from the shown samples, or typed), and a level asked for against each view's deepest.
#pragma once

#include <string>

#include "session/notices.h"
#include "session/viewer_settings.h"
#include "session/viewer_status.h"

namespace polarview {

// The automatic range: one-sided [P(1 - P), P(P)] for one-signed values, else symmetric or each
// side apart (a side without values keeps a sliver, 1e-3, of the other).
ColourInterval automaticInterval(const ColourRangeSettings& settings, const ColourStatus& status);
// The colour range every view uses now (automatic or typed).
ColourInterval colourInterval(const ViewerSettings& settings, const ViewerStatus& status);
// What the colour range does when it is not the paper's zero-centred map, e.g. "all K > 0: range
// 0.8 .. 1.2, one-sided"; empty otherwise.
std::string colourRangeNote(const ViewerSettings& settings, const ViewerStatus& status);
// Automatic colour range on or off; switching it off keeps the current range (typed = automatic).
void setAutomaticRange(ViewerSettings& settings, const ViewerStatus& status, bool automatic);
// Sets the level of the active view (or every view when levels are linked); levels above a view's
// deepest level (ViewStatus::deepestLevel) leave the settings unchanged and post a notice.
void requestLevel(ViewerSettings& settings, const ViewerStatus& status, Notices& notices, int level);

}  // namespace polarview
