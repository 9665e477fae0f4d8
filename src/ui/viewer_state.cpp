#include "ui/viewer_state.h"

#include <algorithm>
#include <cctype>

namespace polarview {
namespace {

std::string lowercase(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

const char* schemeChoiceLabel(SchemeChoice scheme) {
  switch (scheme) {
    case SchemeChoice::CatmullClark: return "CC";
    case SchemeChoice::C2PS: return "C2PS";
    case SchemeChoice::C2PSUniformFirstStep: return "C2PS-U";
    case SchemeChoice::RTS: return "RTS";
    case SchemeChoice::RTSUniformFirstStep: return "RTS-U";
    case SchemeChoice::BPS: return "BPS";
  }
  return "?";
}

const char* schemeChoiceCliName(SchemeChoice scheme) {
  switch (scheme) {
    case SchemeChoice::CatmullClark: return "cc";
    case SchemeChoice::C2PS: return "c2ps";
    case SchemeChoice::C2PSUniformFirstStep: return "c2ps-u";
    case SchemeChoice::RTS: return "rts";
    case SchemeChoice::RTSUniformFirstStep: return "rts-u";
    case SchemeChoice::BPS: return "bps";
  }
  return "?";
}

std::optional<SchemeChoice> parseSchemeChoice(const std::string& name) {
  std::string key = lowercase(name);
  if (key == "c2ps-u" || key == "c2ps-uniform" || key == "c2psu") return SchemeChoice::C2PSUniformFirstStep;
  if (key == "rts-uniform" || key == "rtsu") return SchemeChoice::RTSUniformFirstStep;
  if (key == "catmull-clark" || key == "catmullclark") return SchemeChoice::CatmullClark;
  for (int i = 0; i < kSchemeChoiceCount; ++i) {
    auto scheme = static_cast<SchemeChoice>(i);
    if (key == schemeChoiceCliName(scheme)) return scheme;
  }
  return std::nullopt;
}

RefineOptions refineOptionsFor(SchemeChoice scheme, int level) {
  RefineOptions options;
  options.levels = level;
  options.uniformFirstStep =
      scheme == SchemeChoice::C2PSUniformFirstStep || scheme == SchemeChoice::RTSUniformFirstStep;
  switch (scheme) {
    case SchemeChoice::CatmullClark: options.scheme = Scheme::CatmullClark; break;
    case SchemeChoice::C2PS:
    case SchemeChoice::C2PSUniformFirstStep: options.scheme = Scheme::C2PS; break;
    case SchemeChoice::RTS:
    case SchemeChoice::RTSUniformFirstStep: options.scheme = Scheme::RTS; break;
    case SchemeChoice::BPS: options.scheme = Scheme::BPS; break;
  }
  return options;
}

const char* shadeModeName(ShadingParams::Mode mode) {
  switch (mode) {
    case ShadingParams::Mode::Shaded: return "shaded";
    case ShadingParams::Mode::Gaussian: return "gaussian";
    case ShadingParams::Mode::Mean: return "mean";
    case ShadingParams::Mode::Highlight: return "highlight";
    case ShadingParams::Mode::Reflection: return "reflection";
  }
  return "?";
}

std::optional<ShadingParams::Mode> parseShadeMode(const std::string& name) {
  std::string key = lowercase(name);
  if (key == "lit") return ShadingParams::Mode::Shaded;
  if (key == "zebra") return ShadingParams::Mode::Reflection;
  for (auto mode : {ShadingParams::Mode::Shaded, ShadingParams::Mode::Gaussian, ShadingParams::Mode::Mean,
                    ShadingParams::Mode::Highlight, ShadingParams::Mode::Reflection}) {
    if (key == shadeModeName(mode)) return mode;
  }
  return std::nullopt;
}

}  // namespace polarview
