// View titles: the scheme and level drawn, and why poles fell back to Catmull-Clark.
#include <doctest/doctest.h>

#include <string>

#include "ui/viewer_panels.h"

using namespace polarview;

TEST_CASE("view title: says in a word why every pole fell back to Catmull-Clark") {
  ViewStatus status;
  status.shownScheme = SchemeChoice::C2PS;
  status.shownLevel = 3;
  status.hasSurface = true;
  CHECK(viewTitle(status) == "C2PS \xC2\xB7 3");
  status.polesByCatmullClark = 1;
  status.fallbackReason = "a crease or corner tag touches it at vertex 4 (the polar rules have none)";
  CHECK(viewTitle(status).find("poles by CC (creases)") != std::string::npos);
  status.fallbackReason = "a hole face touches it at vertex 4";
  CHECK(viewTitle(status).find("poles by CC (holes)") != std::string::npos);
  status.fallbackReason = "RTS needs valence >= 5";
  CHECK(viewTitle(status).find("poles by CC (valence < 5)") != std::string::npos);
  status.polesByScheme = 2;
  CHECK(viewTitle(status).find("1 of 3 poles by CC") != std::string::npos);
}

TEST_CASE("new views start on different schemes: C2PS, RTS, BPS, Catmull-Clark (several views are for comparing)") {
  const ViewerSettings settings;
  CHECK(settings.views[0].scheme == SchemeChoice::C2PS);
  CHECK(settings.views[1].scheme == SchemeChoice::RTS);
  CHECK(settings.views[2].scheme == SchemeChoice::BPS);
  CHECK(settings.views[3].scheme == SchemeChoice::CatmullClark);
  for (const View& view : settings.views) CHECK(view.level == 3);
}

TEST_CASE("the strip under the views is as high for light lines as for a curvature map (the model does not move)") {
  ViewerSettings settings;
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  const float curvature = colourBarReserve(settings, 1.0f);
  CHECK(curvature > 0.0f);
  for (ShadingParams::Mode lines : {ShadingParams::Mode::Highlight, ShadingParams::Mode::Reflection}) {
    settings.shading.mode = lines;
    CHECK(colourBarReserve(settings, 1.0f) == curvature);
  }
  const ScreenRect frame{0.0f, 0.0f, 1200.0f, 800.0f};
  settings.shading.mode = ShadingParams::Mode::Gaussian;
  const ScreenRect withBar = layoutViews(1, frame, colourBarReserve(settings, 1.0f)).front();
  settings.shading.mode = ShadingParams::Mode::Reflection;
  const ScreenRect withLegend = layoutViews(1, frame, colourBarReserve(settings, 1.0f)).front();
  CHECK(withBar.h == withLegend.h);
}
