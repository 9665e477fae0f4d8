// Curvature statistics for the colour map's automatic range (CPU, via evaluatePatch).
#include <algorithm>
#include <cmath>

#include "render/patch_renderer.h"

namespace polarview {

std::vector<float> sampleCurvature(const std::vector<Patch>& patches, ShadingParams::Mode mode,
                                   int samplesPerPatch) {
  std::vector<float> values;
  const int n = std::max(samplesPerPatch, 1);
  values.reserve(patches.size() * size_t(n) * n);
  const bool mean = mode == ShadingParams::Mode::Mean;
  for (const Patch& patch : patches)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        // Cell centres: never exactly on the pole, where the (u,v) chart degenerates.
        const SurfacePoint s = evaluatePatch(patch, (i + 0.5) / n, (j + 0.5) / n);
        const double value = mean ? s.mean : s.gaussian;
        if (std::isfinite(value)) values.push_back(static_cast<float>(value));
      }
  return values;
}

float suggestCurvatureRange(std::vector<float> values, float quantile) {
  if (values.empty()) return 1.0f;
  for (float& v : values) v = std::abs(v);
  const size_t k = std::min(values.size() - 1,
                            static_cast<size_t>(std::clamp(quantile, 0.0f, 1.0f) * (values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  const float range = values[k];
  return range > 0.0f && std::isfinite(range) ? range : 1.0f;
}

}  // namespace polarview
