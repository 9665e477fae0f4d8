#include "core/subdiv/scheme.h"

namespace polarview {

const char* schemeName(Scheme s) {
  switch (s) {
    case Scheme::CatmullClark: return "cc";
    case Scheme::C2PS: return "c2ps";
    case Scheme::RTS: return "rts";
    case Scheme::BPS: return "bps";
  }
  return "?";
}

std::optional<Scheme> parseScheme(const std::string& name) {
  if (name == "cc") return Scheme::CatmullClark;
  if (name == "c2ps") return Scheme::C2PS;
  if (name == "rts") return Scheme::RTS;
  if (name == "bps") return Scheme::BPS;
  return std::nullopt;
}

}  // namespace polarview
