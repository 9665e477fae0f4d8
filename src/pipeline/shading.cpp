// The colours shared with the shaders, on the CPU (see shading.h).
#include "pipeline/shading.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "pipeline/weighted_statistics.h"

namespace polarview {
namespace {

// Colour-map stops shared by colorMapCpu (mirror of shaders/common/colormap.glsl).
glm::vec3 fiveStops(float t, const glm::vec3 (&c)[5]) {
  const float x = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const int k = std::min(static_cast<int>(x), 3);
  return glm::mix(c[k], c[k + 1], x - static_cast<float>(k));
}

}  // namespace

const std::vector<ShadingModeInfo>& shadingModes() {
  using Mode = ShadingParams::Mode;
  static const std::vector<ShadingModeInfo> modes = {
      {Mode::Shaded, "shaded", "lit", "Lit", 'L', false, false},
      {Mode::Gaussian, "gaussian", "", "Gaussian K", 'G', true, false},
      {Mode::Mean, "mean", "", "Mean H", 'M', true, false},
      {Mode::Highlight, "highlight", "", "Highlight lines", 'H', false, true},
      {Mode::Reflection, "reflection", "zebra", "Reflection lines / zebra", 'Z', false, true},
  };
  return modes;
}

const ShadingModeInfo& shadingModeInfo(ShadingParams::Mode mode) {
  for (const ShadingModeInfo& info : shadingModes())
    if (info.mode == mode) return info;
  return shadingModes().front();
}

glm::vec3 patchKindColor(PatchKind kind) {
  switch (kind) {
    case PatchKind::Regular: return {0.15f, 0.15f, 0.15f};
    case PatchKind::Boundary: return {0.45f, 0.30f, 0.10f};
    case PatchKind::PolarRing: return {0.10f, 0.35f, 0.85f};
    case PatchKind::PoleCap: return {0.85f, 0.10f, 0.10f};
    case PatchKind::EndCap: return {0.70f, 0.10f, 0.75f};
  }
  return {0.5f, 0.5f, 0.5f};
}

glm::vec3 ringColor(int ring) {
  // A qualitative palette (Tableau 10 subset), cycling.
  static const glm::vec3 palette[8] = {{0.12f, 0.47f, 0.71f}, {1.00f, 0.50f, 0.05f},
                                       {0.17f, 0.63f, 0.17f}, {0.84f, 0.15f, 0.16f},
                                       {0.58f, 0.40f, 0.74f}, {0.55f, 0.34f, 0.29f},
                                       {0.89f, 0.47f, 0.76f}, {0.09f, 0.75f, 0.81f}};
  if (ring < 0) return {0.35f, 0.35f, 0.35f};
  return palette[ring % 8];
}

double colourBarPosition(double value, const ColourInterval& range) {
  const auto& [low, high] = range;
  if (!range.oneSided()) {  // zero in the middle, two slopes
    const double side = value >= 0.0 ? high : -low;
    return 0.5 + 0.5 * std::clamp(value / side, -1.0, 1.0);
  }
  // One-sided. Here values are the world's (1e-300 .. 1e300): no floor on the width.
  return high > low ? std::clamp((value - low) / (high - low), 0.0, 1.0) : 0.5;
}

double colourBarValue(double position, const ColourInterval& range) {
  const auto& [low, high] = range;
  if (!range.oneSided()) return position < 0.5 ? (1.0 - 2.0 * position) * low : (2.0 * position - 1.0) * high;
  return low + position * (high - low);
}

glm::vec3 colorMapCpu(ShadingParams::ColorMap map, double value, const ColourInterval& range) {
  // The map's t in [-1, 1]: the whole map when zero is inside the range, else the half of the
  // range's sign (positive: t in [0, 1], negative: [-1, 0]); see the shaders' curvatureColor.
  const double p = colourBarPosition(value, range);
  const float t = float(!range.oneSided() ? 2.0 * p - 1.0 : range.high > 0.0 ? p : p - 1.0);
  switch (map) {
    case ShadingParams::ColorMap::CoolWarm: {
      static const glm::vec3 stops[5] = {{0.230f, 0.299f, 0.754f}, {0.552f, 0.690f, 0.996f},
                                         {0.865f, 0.865f, 0.865f}, {0.958f, 0.603f, 0.482f},
                                         {0.706f, 0.016f, 0.150f}};
      return fiveStops(0.5f * (t + 1.0f), stops);
    }
    case ShadingParams::ColorMap::Viridis: {
      static const glm::vec3 stops[5] = {{0.267f, 0.005f, 0.329f}, {0.229f, 0.322f, 0.546f},
                                         {0.128f, 0.567f, 0.551f}, {0.369f, 0.789f, 0.383f},
                                         {0.993f, 0.906f, 0.144f}};
      return fiveStops(0.5f * (t + 1.0f), stops);
    }
    case ShadingParams::ColorMap::Magnitude: {
      static const glm::vec3 stops[5] = {{0.0f, 0.0f, 0.45f}, {0.0f, 0.3f, 1.0f}, {0.0f, 0.9f, 0.9f},
                                         {1.0f, 0.9f, 0.0f}, {0.85f, 0.0f, 0.0f}};
      return fiveStops(std::abs(t), stops);
    }
    case ShadingParams::ColorMap::Paper:
    default: {
      // Hue 240 (blue) at -range, 120 (green) on |t| <= kPaperGreenBand, 0 (red) at +range.
      constexpr float kPaperGreenBand = 0.1f;
      const float s = std::copysign(std::max(std::abs(t) - kPaperGreenBand, 0.0f), t) / (1.0f - kPaperGreenBand);
      const float hue = (1.0f - s) * 2.0f;
      glm::vec3 rgb;
      const float offsets[3] = {0.0f, 4.0f, 2.0f};
      for (int c = 0; c < 3; ++c)
        rgb[c] = std::clamp(std::abs(std::fmod(hue + offsets[c], 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
      return 0.95f * rgb;
    }
  }
}

ColourStatistics colourStatistics(const std::vector<double>& values, const std::vector<double>& weights, float quantile) {
  ColourStatistics statistics;
  const double upper = symmetricRangeFraction(quantile);
  const std::vector<double> percentiles =
      weightedPercentiles(values, weights, {1.0 - upper, upper, 1.0 - quantile, double(quantile)});
  statistics.symmetricRange = symmetricRange(percentiles[0], percentiles[1]);
  statistics.percentiles = {percentiles[2], percentiles[3]};
  const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
  statistics.min = *lowest;
  statistics.max = *highest;
  // A one-sided range needs a width: a sphere's K can be one value to all digits.
  const int sign = statistics.oneSign();
  ColourInterval& p = statistics.percentiles;
  const double narrowest = 1e-6 * std::max(std::abs(p.low), std::abs(p.high));
  if (sign != 0 && !(p.high - p.low >= narrowest)) {
    const double middle = 0.5 * (p.low + p.high);
    p = {middle - 0.5 * narrowest, middle + 0.5 * narrowest};
    if (sign > 0 ? p.low < 0.0 : p.high > 0.0) p = sign > 0 ? ColourInterval{0.0, narrowest} : ColourInterval{-narrowest, 0.0};
  }
  return statistics;
}

std::vector<float> weightedHistogram(const std::vector<double>& values, const std::vector<double>& weights,
                                     const ColourInterval& range, int bins) {
  std::vector<float> histogram(size_t(std::max(bins, 1)), 0.0f);
  if (!(range.high > range.low)) return histogram;
  for (size_t i = 0; i < values.size() && i < weights.size(); ++i) {
    if (!(weights[i] > 0.0) || !std::isfinite(values[i])) continue;
    const double p = colourBarPosition(values[i], range);  // as the bar: two slopes or one-sided
    const int bin = std::min(int(p * double(histogram.size())), int(histogram.size()) - 1);
    histogram[size_t(bin)] += float(weights[i]);
  }
  const float largest = *std::max_element(histogram.begin(), histogram.end());
  if (largest > 0.0f)
    for (float& h : histogram) h /= largest;
  return histogram;
}

glm::vec3 perpendicularTo(const glm::vec3& axis, const glm::vec3& hint) {
  glm::vec3 p = hint - glm::dot(hint, axis) * axis;
  if (glm::dot(p, p) < 1e-8f) {  // hint along the axis: any perpendicular, the least aligned axis's
    p = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    p -= glm::dot(p, axis) * axis;
  }
  return glm::normalize(p);
}

}  // namespace polarview
