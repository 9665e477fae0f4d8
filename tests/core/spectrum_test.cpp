// Spectra of subdivision matrices (spectrum.h): Catmull-Clark's 1-ring matrix against the closed
// forms of its eigenvalues, and the `spectrum` command's entry point for RTS (Table 1).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "core/subdiv/spectrum.h"

using namespace polarview;

TEST_CASE("spectrum: Catmull-Clark at valence n has 1, the subdominant pair of the closed form, then 1/4-like values") {
  constexpr double kPi = 3.14159265358979323846;
  for (int n = 3; n <= 16; ++n) {
    const std::vector<TaggedEigenvalue> s = schemeSpectrum(Scheme::CatmullClark, n);
    REQUIRE(s.size() == size_t(2 * n + 1));
    // lambda = (5 + cos(2 pi / n) + cos(pi / n) sqrt(18 + 2 cos(2 pi / n))) / 16 (Doo-Sabin / Ball-Storry
    // analysis of Catmull-Clark; 1/2 at n = 4).
    const double c = std::cos(2.0 * kPi / n);
    const double lambda = (5.0 + c + std::cos(kPi / n) * std::sqrt(18.0 + 2.0 * c)) / 16.0;
    CAPTURE(n);
    CHECK(std::abs(s[0].value - Complex(1.0)) < 1e-12);
    CHECK(std::abs(s[1].value - Complex(lambda)) < 1e-10);
    CHECK(std::abs(s[2].value - Complex(lambda)) < 1e-10);
    CHECK(std::abs(s[3].value) < lambda);
  }
  const std::vector<TaggedEigenvalue> regular = schemeSpectrum(Scheme::CatmullClark, 4);
  for (int k : {3, 4, 5}) CHECK(std::abs(regular[size_t(k)].value - Complex(0.25)) < 1e-12);
}

TEST_CASE("spectrum: RTS gives Table 1 at every valence from 5 to 64; C2PS has no stationary matrix") {
  for (int n : {5, 7, 16, 64}) {
    const std::vector<TaggedEigenvalue> s = schemeSpectrum(Scheme::RTS, n);
    const double table1[] = {1.0, 0.5, 0.5, 0.25, 0.25, 0.25};
    CAPTURE(n);
    for (int k = 0; k < 6; ++k) CHECK(std::abs(s[size_t(k)].value - Complex(table1[k])) < 1e-12);
    CHECK(std::abs(s[6].value) == doctest::Approx(1.0 / 12.0).epsilon(1e-9));
  }
  CHECK_THROWS_AS(schemeSpectrum(Scheme::C2PS, 6), std::invalid_argument);
}
