// The schemes a view can show, named as the panels and the command line name them, and the
// shading modes' names: plain data shared by the surface pipeline, the panels and the commands.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/subdiv/scheme.h"
#include "pipeline/shading.h"

namespace polarview {

// The six schemes a view can show (C2PS and RTS twice: with and without the uniform first step of
// the paper's Section 6, which its Fig. 11 uses).
enum class SchemeChoice : uint8_t { CatmullClark, C2PS, C2PSUniformFirstStep, RTS, RTSUniformFirstStep, BPS };
constexpr int kSchemeChoiceCount = 6;
// Hard cap of the level (keys 0-9 and the slider stop earlier where the model's face budget says
// so: ViewStatus::deepestLevel).
constexpr int kMaxLevel = 24;
constexpr int kPatchKindCount = 5;  // PatchKind::Regular .. EndCap

// On-screen name: "CC", "C2PS", "C2PS-U", "RTS", "RTS-U", "BPS".
const char* schemeChoiceLabel(SchemeChoice scheme);
// Command-line name: "cc", "c2ps", "c2ps-u", "rts", "rts-u", "bps".
const char* schemeChoiceCliName(SchemeChoice scheme);
// The choice that shows `variant` (every variant of the scheme table has one). [O(choices)]
std::optional<SchemeChoice> schemeChoiceFor(const SchemeVariant& variant);
// The choice a name stands for: parseSchemeVariant's names (core/subdiv/scheme.h, the one parser:
// case-insensitive, "c2ps-uniform", "catmull-clark", ...). [O(choices)]
std::optional<SchemeChoice> parseSchemeChoice(const std::string& name);
// The scheme-table row and first step a choice stands for (its traits: schemeTraits(variant.scheme)).
SchemeVariant schemeChoiceVariant(SchemeChoice scheme);
// The command-line names of the choices `accepts` takes (every one without it), in menu order,
// joined by `separator`: "cc, c2ps, c2ps-u, rts, rts-u, bps". Usage texts and messages list the
// schemes from here rather than typing them. [O(choices)]
std::string schemeChoiceNames(const std::string& separator, const std::function<bool(SchemeChoice)>& accepts = {});
// Refinement options of a scheme choice at `level`.
RefineOptions refineOptionsFor(SchemeChoice scheme, int level);
// Name of a shading mode for labels ("shaded", "gaussian", "mean", "highlight", "reflection").
const char* shadeModeName(ShadingParams::Mode mode);
std::optional<ShadingParams::Mode> parseShadeMode(const std::string& name);

}  // namespace polarview
