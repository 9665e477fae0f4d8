// What a view's surface is a function of: the model (its generation and points revision), the
// scheme and the level. The key of the surface cache, the jobs and the GPU mirror.
#pragma once

#include <cstdint>

#include "pipeline/scheme_choice.h"

namespace polarview {

// What a surface is a function of.
struct SurfaceKey {
  uint64_t model = 0;  // model generation (bumped on every load; the topology)
  SchemeChoice scheme = SchemeChoice::C2PS;
  int level = 0;
  uint64_t points = 0;  // revision of the model's points (bumped by every edit)
  bool operator==(const SurfaceKey& o) const { return sameTopology(o) && points == o.points; }
  bool operator!=(const SurfaceKey& o) const { return !(*this == o); }
  // Same model, scheme and level: the surfaces differ at most in their points, so one is the other
  // after refreshSurface.
  bool sameTopology(const SurfaceKey& o) const { return model == o.model && scheme == o.scheme && level == o.level; }
};

}  // namespace polarview
