// What a page's address says about its views (docs/web.md, "A view is a link"): the URL parameters
// scheme, level, shade, camera (and panels) read into plain settings, and written back so that the
// page's link reproduces what it shows. GL-free; the page's program (web_main.cpp) applies them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pipeline/orbit_camera.h"
#include "pipeline/scheme_choice.h"
#include "pipeline/shading.h"

namespace polarview {

constexpr int kMaxWebViews = 4;

// The page's settings: the desktop's defaults for a first visit (two views, C2PS beside
// Catmull-Clark, level 3, Gaussian curvature).
struct WebSettings {
  std::vector<SchemeChoice> schemes{SchemeChoice::C2PS, SchemeChoice::CatmullClark};  // 1..4 views
  int level = 3;
  ShadingParams::Mode shade = ShadingParams::Mode::Gaussian;
  std::optional<OrbitCamera> camera;  // none: framed to the model
  bool panels = true;                 // the ImGui panel column (panels=0 hides it: embedding, tests)
};

// Reads a query string ("scheme=c2ps,cc&level=3&shade=gaussian", with or without the leading '?',
// percent-encoded or not) over the defaults. A parameter it cannot read is left at its default and
// its reason appended to `errors` (shown on the page); unknown parameters are ignored. [O(length)]
WebSettings parseWebQuery(const std::string& query, std::vector<std::string>* errors);

// The query string of `settings` with `camera` ("?scheme=c2ps,cc&level=3&shade=gaussian&camera=..."),
// the camera as cameraToJson writes it, percent-encoded. parseWebQuery reads it back. [O(1)]
std::string makeWebQuery(const WebSettings& settings, const OrbitCamera& camera);

// Percent-decoding ('+' is a space) and encoding of one query value. [O(length)]
std::string percentDecode(const std::string& text);
std::string percentEncode(const std::string& text);

}  // namespace polarview
