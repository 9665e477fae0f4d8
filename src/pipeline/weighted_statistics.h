// Area-weighted percentiles of curvature samples: the automatic colour ranges (shading.h).
#pragma once

#include <vector>

namespace polarview {

// The weighted percentile: the first value (in order) where the running weight reaches `fraction` of
// the total; 0 when there is no weight. [O(n log n)]
double weightedPercentile(const std::vector<double>& values, const std::vector<double>& weights, double fraction);
// The same at each of `fractions`, from one sort (a colour range needs four). [O(n log n)]
std::vector<double> weightedPercentiles(const std::vector<double>& values, const std::vector<double>& weights,
                                        const std::vector<double>& fractions);
// The symmetric colour range max(-P(1 - quantile), P(quantile)) of the weighted percentiles P of
// the signed values (quantile 0.95: the 5th and 95th percentiles), so each tail may saturate on at
// most 1 - quantile of the weight; 1 when there is no weight or the range would be 0. [O(n log n)]
double weightedSymmetricRange(const std::vector<double>& values, const std::vector<double>& weights, float quantile);
// Its parts: the fraction whose percentiles it reads (quantile clamped to [0.5, 1]: P(1 - f) and
// P(f)), and the range from those two percentiles.
double symmetricRangeFraction(float quantile);
double symmetricRange(double lowPercentile, double highPercentile);

}  // namespace polarview
