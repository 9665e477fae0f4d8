#include "core/subdiv/polar_rules.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/mesh/constants.h"

namespace polarview {

namespace {

// (cos, sin) of the multiples 1..kMaxLinkFrequency of an angle, by the addition theorem.
std::array<std::array<double, 2>, kMaxLinkFrequency + 1> angleMultiples(const std::array<double, 2>& unit) {
  std::array<std::array<double, 2>, kMaxLinkFrequency + 1> m{};
  m[0] = {1.0, 0.0};
  for (int a = 1; a <= kMaxLinkFrequency; ++a)
    m[a] = {m[a - 1][0] * unit[0] - m[a - 1][1] * unit[1], m[a - 1][1] * unit[0] + m[a - 1][0] * unit[1]};
  return m;
}

}  // namespace

std::array<double, 2> unitCircle(long long k, long long m) {
  long long r = ((k % m) + m) % m;
  double angle = kTwoPi * double(r) / double(m);
  return {std::cos(angle), std::sin(angle)};
}

Point LinkFourierSums::trigonometricPart(const std::array<double, kMaxLinkFrequency + 1>& weight,
                                         const std::array<double, 2>& unit) const {
  auto multiple = angleMultiples(unit);
  Point sum{0.0};
  for (int a = 1; a <= kMaxLinkFrequency; ++a)
    if (weight[a] != 0.0) sum += weight[a] * (multiple[a][0] * cosSum[a] + multiple[a][1] * sinSum[a]);
  return sum;
}

Point polarVertexRule(const Point& pole, const Point* link1, int n) { return 0.75 * pole + 0.25 * linkMean(link1, n); }

Point linkMean(const Point* link, int n) {
  Point sum{0.0};
  for (int h = 0; h < n; ++h) sum += link[h];
  return sum / double(n);
}

LinkFourierSums linkFourierSums(const Point* link, int n, int maxFrequency) {
  if (maxFrequency < 1 || maxFrequency > kMaxLinkFrequency)
    throw std::invalid_argument("linkFourierSums: maxFrequency must be 1.." + std::to_string(kMaxLinkFrequency));
  LinkFourierSums sums;
  for (int h = 0; h < n; ++h) {
    sums.mean += link[h];
    auto multiple = angleMultiples(unitCircle(h, n));
    for (int a = 1; a <= maxFrequency; ++a) {
      sums.cosSum[a] += multiple[a][0] * link[h];
      sums.sinSum[a] += multiple[a][1] * link[h];
    }
  }
  double inverseN = 1.0 / double(n);
  sums.mean *= inverseN;
  for (int a = 1; a <= maxFrequency; ++a) {
    sums.cosSum[a] *= inverseN;
    sums.sinSum[a] *= inverseN;
  }
  return sums;
}

void refinePeriodicLink(const Point* link, int n, Point* out) {
  for (int j = 0; j < n; ++j) {
    const Point& before = link[j == 0 ? n - 1 : j - 1];
    const Point& after = link[j + 1 == n ? 0 : j + 1];
    out[2 * j] = radialEvenRule(before, link[j], after);  // same 1/8, 3/4, 1/8 weights along the link
    out[2 * j + 1] = radialOddRule(link[j], after);
  }
}

void refineOuterLinksRadially(const Point* links, int width, int linkCount, Point* out) {
  if (linkCount < 2) throw std::invalid_argument("refineOuterLinksRadially: needs at least links 1 and 2");
  auto oldLink = [&](int i) { return links + size_t(i - 1) * width; };        // i = 1..K
  auto newLink = [&](int i) { return out + size_t(i - 3) * width; };          // i = 3..2K-1
  for (int i = 1; i + 1 <= linkCount; ++i) {
    // new link 2i+1 (edge points between old links i and i+1)
    const Point* at = oldLink(i);
    const Point* after = oldLink(i + 1);
    Point* odd = newLink(2 * i + 1);
    for (int j = 0; j < width; ++j) odd[j] = radialOddRule(at[j], after[j]);
    // new link 2i+2 (vertex points of old link i+1), when old link i+2 exists
    if (i + 2 <= linkCount) {
      const Point* beyond = oldLink(i + 2);
      Point* even = newLink(2 * i + 2);
      for (int j = 0; j < width; ++j) even[j] = radialEvenRule(at[j], after[j], beyond[j]);
    }
  }
}

}  // namespace polarview
