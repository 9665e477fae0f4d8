#include "pipeline/weighted_statistics.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace polarview {

double weightedPercentile(const std::vector<double>& values, const std::vector<double>& weights, double fraction) {
  std::vector<std::pair<double, double>> sorted;  // (value, weight) by value
  double total = 0.0;
  for (size_t i = 0; i < values.size() && i < weights.size(); ++i) {
    if (!(weights[i] > 0.0) || !std::isfinite(values[i])) continue;
    sorted.emplace_back(values[i], weights[i]);
    total += weights[i];
  }
  if (sorted.empty() || !(total > 0.0)) return 0.0;
  std::sort(sorted.begin(), sorted.end());
  const double needed = std::clamp(fraction, 0.0, 1.0) * total;
  double sum = 0.0;
  for (const auto& [value, weight] : sorted) {
    sum += weight;
    if (sum >= needed) return value;
  }
  return sorted.back().first;
}

double weightedSymmetricRange(const std::vector<double>& values, const std::vector<double>& weights, float quantile) {
  const double upper = std::clamp(double(quantile), 0.5, 1.0);
  const double range = std::max(-weightedPercentile(values, weights, 1.0 - upper), weightedPercentile(values, weights, upper));
  return range > 0.0 && std::isfinite(range) ? range : 1.0;  // also when there is no weight
}

}  // namespace polarview
