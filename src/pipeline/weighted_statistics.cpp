#include "pipeline/weighted_statistics.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace polarview {

std::vector<double> weightedPercentiles(const std::vector<double>& values, const std::vector<double>& weights,
                                        const std::vector<double>& fractions) {
  std::vector<std::pair<double, double>> sorted;  // (value, weight) by value
  double total = 0.0;
  for (size_t i = 0; i < values.size() && i < weights.size(); ++i) {
    if (!(weights[i] > 0.0) || !std::isfinite(values[i])) continue;
    sorted.emplace_back(values[i], weights[i]);
    total += weights[i];
  }
  std::vector<double> percentiles(fractions.size(), 0.0);
  if (sorted.empty() || !(total > 0.0)) return percentiles;
  std::sort(sorted.begin(), sorted.end());
  for (size_t k = 0; k < fractions.size(); ++k) {
    const double needed = std::clamp(fractions[k], 0.0, 1.0) * total;
    double sum = 0.0;
    percentiles[k] = sorted.back().first;
    for (const auto& [value, weight] : sorted) {
      sum += weight;
      if (sum >= needed) {
        percentiles[k] = value;
        break;
      }
    }
  }
  return percentiles;
}

double weightedPercentile(const std::vector<double>& values, const std::vector<double>& weights, double fraction) {
  return weightedPercentiles(values, weights, {fraction})[0];
}

double symmetricRangeFraction(float quantile) { return std::clamp(double(quantile), 0.5, 1.0); }

double symmetricRange(double lowPercentile, double highPercentile) {
  const double range = std::max(-lowPercentile, highPercentile);
  return range > 0.0 && std::isfinite(range) ? range : 1.0;  // also when there is no weight
}

double weightedSymmetricRange(const std::vector<double>& values, const std::vector<double>& weights, float quantile) {
  const double upper = symmetricRangeFraction(quantile);
  const std::vector<double> p = weightedPercentiles(values, weights, {1.0 - upper, upper});
  return symmetricRange(p[0], p[1]);
}

}  // namespace polarview
