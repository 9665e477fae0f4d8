// Names of the scheme choices and shading modes (see scheme_choice.h).
#include "pipeline/scheme_choice.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace polarview {
namespace {

std::string lowercase(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

namespace {
// The viewer's schemes in menu order, each a row of the scheme table (core/subdiv/scheme.h) and a
// first step: the labels, names and refine options below all come from there.
constexpr SchemeVariant kChoiceVariants[kSchemeChoiceCount] = {
    {Scheme::CatmullClark, false}, {Scheme::C2PS, false}, {Scheme::C2PS, true},
    {Scheme::RTS, false},          {Scheme::RTS, true},   {Scheme::BPS, false}};

// Label and name of every choice, made once (the functions hand out C strings).
const std::array<std::pair<std::string, std::string>, kSchemeChoiceCount>& choiceTexts() {
  static const auto texts = [] {
    std::array<std::pair<std::string, std::string>, kSchemeChoiceCount> out;
    for (int i = 0; i < kSchemeChoiceCount; ++i)
      out[size_t(i)] = {schemeVariantLabel(kChoiceVariants[i]), schemeVariantName(kChoiceVariants[i])};
    return out;
  }();
  return texts;
}
}  // namespace

const char* schemeChoiceLabel(SchemeChoice scheme) { return choiceTexts()[size_t(scheme)].first.c_str(); }
const char* schemeChoiceCliName(SchemeChoice scheme) { return choiceTexts()[size_t(scheme)].second.c_str(); }

std::optional<SchemeChoice> schemeChoiceFor(const SchemeVariant& variant) {
  for (int i = 0; i < kSchemeChoiceCount; ++i)
    if (kChoiceVariants[i].scheme == variant.scheme && kChoiceVariants[i].uniformFirstStep == variant.uniformFirstStep)
      return static_cast<SchemeChoice>(i);
  return std::nullopt;
}

std::optional<SchemeChoice> parseSchemeChoice(const std::string& name) {
  const std::optional<SchemeVariant> variant = parseSchemeVariant(name);
  return variant ? schemeChoiceFor(*variant) : std::nullopt;
}

SchemeVariant schemeChoiceVariant(SchemeChoice scheme) { return kChoiceVariants[int(scheme)]; }

std::string schemeChoiceNames(const std::string& separator, const std::function<bool(SchemeChoice)>& accepts) {
  std::string names;
  for (int i = 0; i < kSchemeChoiceCount; ++i) {
    const auto scheme = static_cast<SchemeChoice>(i);
    if (accepts && !accepts(scheme)) continue;
    names += (names.empty() ? "" : separator) + schemeChoiceCliName(scheme);
  }
  return names;
}

RefineOptions refineOptionsFor(SchemeChoice scheme, int level) {
  const SchemeVariant variant = kChoiceVariants[int(scheme)];
  return RefineOptions{variant.scheme, level, variant.uniformFirstStep};
}

const char* shadeModeName(ShadingParams::Mode mode) { return shadingModeInfo(mode).name; }

std::optional<ShadingParams::Mode> parseShadeMode(const std::string& name) {
  const std::string key = lowercase(name);
  for (const ShadingModeInfo& info : shadingModes())
    if (key == info.name || key == info.alias) return info.mode;
  return std::nullopt;
}

}  // namespace polarview
