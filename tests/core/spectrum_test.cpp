// Spectra of subdivision matrices (spectrum.h): Catmull-Clark's 1-ring matrix against the closed
// forms of its eigenvalues and limit mask, the `spectrum` command's entry point for RTS (Table 1's
// eigenvalues and eigenvectors), eigenpair residuals and bi-orthonormality for RTS, BPS and
// Catmull-Clark, and C2PS on RTS's eigenvectors (Lemma 5, (30)).
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/mesh/constants.h"
#include "core/subdiv/spectrum.h"

using namespace polarview;

TEST_CASE("spectrum: Catmull-Clark at valence n has 1, the subdominant pair of the closed form, then 1/4-like values") {
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

namespace {

// Largest |imaginary part| of a vector: the eigenvectors of real eigenvalues must be real.
double largestImaginary(const std::vector<Complex>& v) {
  double m = 0.0;
  for (const Complex& x : v) m = std::max(m, std::abs(x.imag()));
  return m;
}

// The real factor c with v = c u (u's largest entry non-zero), or 0 when v is not a multiple of u
// to `tolerance` (relative to v's largest entry).
double multipleOf(const std::vector<Complex>& v, const std::vector<double>& u, double tolerance) {
  size_t top = 0;
  for (size_t i = 0; i < u.size(); ++i)
    if (std::abs(u[i]) > std::abs(u[top])) top = i;
  const double c = v[top].real() / u[top];
  double scale = 0.0, error = 0.0;
  for (size_t i = 0; i < u.size(); ++i) scale = std::max(scale, std::abs(v[i])), error = std::max(error, std::abs(v[i] - c * u[i]));
  return error <= tolerance * scale ? c : 0.0;
}

}  // namespace

TEST_CASE("spectrum: right and left eigenvectors satisfy A v = lambda v, w^T A = lambda w^T and w_k^T v_l = delta_kl") {
  struct Case {
    Scheme scheme;
    int n;
    size_t count;
  };
  // RTS: 1, 1/2 (x2), 1/4 (x3), then 1/12 in every block; BPS: its 1, 1/2, 1/4s (its 1/8 in block
  // n/2 is defective at n = 6); Catmull-Clark: to the 1/4-like values (at n = 4 the regular 1/4 is
  // threefold over blocks 0 and 2).
  for (const Case& c : {Case{Scheme::RTS, 5, 9}, Case{Scheme::RTS, 6, 8}, Case{Scheme::RTS, 16, 10},
                        Case{Scheme::RTS, 64, 8}, Case{Scheme::BPS, 6, 6}, Case{Scheme::BPS, 12, 6},
                        Case{Scheme::CatmullClark, 3, 6}, Case{Scheme::CatmullClark, 4, 9},
                        Case{Scheme::CatmullClark, 7, 12}}) {
    const std::string scheme = schemeName(c.scheme);
    CAPTURE(scheme);
    CAPTURE(c.n);
    const Matrix a = schemeMatrix(c.scheme, c.n);
    const std::vector<EigenPair> pairs = schemeEigenPairs(c.scheme, c.n, c.count);
    const std::vector<TaggedEigenvalue> values = schemeSpectrum(c.scheme, c.n);
    REQUIRE(pairs.size() == c.count);
    for (const EigenPair& p : pairs) REQUIRE(p.right.size() == a.size());
    for (size_t k = 0; k < pairs.size(); ++k) {
      CAPTURE(k);
      CHECK(std::abs(pairs[k].value - values[k].value) < 1e-14);
      CHECK(eigenPairResidual(a, pairs[k]) < 1e-12);
      CHECK(largestImaginary(pairs[k].right) < 1e-14);  // every leading eigenvalue here is real (|v| <= 1)
      CHECK(largestImaginary(pairs[k].left) < 1e-13);
      for (size_t l = 0; l < pairs.size(); ++l) {
        Complex dot = 0.0;
        for (size_t i = 0; i < a.size(); ++i) dot += pairs[k].left[i] * pairs[l].right[i];
        CAPTURE(l);
        CHECK(std::abs(dot - (k == l ? 1.0 : 0.0)) < 1e-12);
      }
    }
  }
}

TEST_CASE("spectrum: RTS's eigenvectors are Table 1's: the characteristic map's cos/sin modes and the quadratic modes") {
  for (int n : {5, 6, 7, 16, 64}) {
    CAPTURE(n);
    const std::vector<EigenPair> pairs = schemeEigenPairs(Scheme::RTS, n, 6);
    const double table1[] = {1.0, 0.5, 0.5, 0.25, 0.25, 0.25};
    const int alphas[] = {0, 1, n - 1, 0, 2, n - 2};
    const FourierMode modes[] = {FourierMode::Single, FourierMode::Cos, FourierMode::Sin,
                                 FourierMode::Single, FourierMode::Cos, FourierMode::Sin};
    // Table 1's profiles, read as radial cubic B-spline control points at unit knots (link i at
    // r = i): 1, r (i) and r^2 (i^2 - 1/3), Lemma 2 (20)-(22); the pole carries the alpha = 0 modes
    // only. Left profiles w^ as Table 1 (with (27)'s misprints corrected, docs/misprints.md).
    auto profile = [](int k, int i) {
      if (k == 0) return 1.0;
      if (k <= 2) return double(i);
      return i == 0 && k > 3 ? 0.0 : i * i - 1.0 / 3.0;
    };
    const double left[6][2] = {{2.0 / 3.0, 1.0 / 3.0}, {0, 2}, {0, 2}, {-1, 1}, {0, 3}, {0, 3}};
    const int frequency[] = {0, 1, 1, 0, 2, 2};
    for (int k = 0; k < 6; ++k) {
      CAPTURE(k);
      const EigenPair& p = pairs[size_t(k)];
      CHECK(std::abs(p.value - Complex(table1[k])) < 1e-12);
      CHECK(p.alpha == alphas[k]);
      CHECK(p.mode == modes[k]);
      // (14): v_ij = v^_i op_k(j/n) with op = 1, cos, sin of frequency alpha; (26): w_ij = w^_i op_k(j/n) / n.
      std::vector<double> v(size_t(6 * n)), w(size_t(6 * n));
      for (int j = 0; j < n; ++j) {
        const double t = kTwoPi * frequency[k] * j / n;
        const double op = modes[k] == FourierMode::Sin ? std::sin(t) : std::cos(t);
        for (int i = 0; i < 6; ++i) {
          v[size_t(polarMatrixIndex(i, j))] = profile(k, i) * op;
          w[size_t(polarMatrixIndex(i, j))] = (i < 2 ? left[k][i] : 0.0) * op / n;
        }
      }
      const double c = multipleOf(p.right, v, 1e-12);
      REQUIRE(c != 0.0);
      // v = c v_Table1 and w^T v = 1 force w = w_Table1 / c, and so the profiles.
      for (size_t i = 0; i < w.size(); ++i) CHECK(std::abs(p.left[i].real() * c - w[i]) < 1e-12);
      for (int i = 0; i < 6; ++i) {
        CHECK(std::abs(p.rightProfile[size_t(i)] - c * profile(k, i)) < 1e-12);
        CHECK(std::abs(p.leftProfile[size_t(i)] * c - (i < 2 ? left[k][i] : 0.0)) < 1e-12);
      }
    }
  }
}

TEST_CASE("spectrum: Catmull-Clark's eigenvectors: the limit mask on the left of 1, cos/sin modes for the subdominant pair") {
  for (int n = 3; n <= 12; ++n) {
    CAPTURE(n);
    const std::vector<EigenPair> pairs = schemeEigenPairs(Scheme::CatmullClark, n, 3);
    // lambda = 1: v = 1 (affine invariance), w = the limit-position mask
    // (n^2 v + 4 sum e_j + sum f_j) / (n (n + 5)) (Halstead, Kass & DeRose 1993).
    const double d = n * (n + 5.0);
    CHECK(multipleOf(pairs[0].right, std::vector<double>(size_t(2 * n + 1), 1.0), 1e-13) == doctest::Approx(1.0));
    CHECK(std::abs(pairs[0].left[0] - n * n / d) < 1e-13);
    for (int j = 0; j < n; ++j) {
      CHECK(std::abs(pairs[0].left[size_t(1 + j)] - 4.0 / d) < 1e-13);
      CHECK(std::abs(pairs[0].left[size_t(1 + n + j)] - 1.0 / d) < 1e-13);
    }
    // The subdominant pair: e_j at angle j/n, f_j half-way to e_{j+1}, both cos (resp. sin) of the
    // angle with their own radial factors, the centre 0: the characteristic map's x and y.
    REQUIRE(pairs[1].mode == FourierMode::Cos);
    REQUIRE(pairs[2].mode == FourierMode::Sin);
    for (int k : {1, 2}) {
      const EigenPair& p = pairs[size_t(k)];
      const double e = k == 1 ? p.right[1].real() : p.right[2].real() / std::sin(kTwoPi / n);
      const double fCos = std::cos(kTwoPi * 0.5 / n), fSin = std::sin(kTwoPi * 0.5 / n);
      const double f = k == 1 ? p.right[size_t(1 + n)].real() / fCos : p.right[size_t(1 + n)].real() / fSin;
      CHECK(std::abs(p.right[0]) < 1e-14);
      for (int j = 0; j < n; ++j) {
        auto op = [&](double t) { return k == 1 ? std::cos(kTwoPi * t) : std::sin(kTwoPi * t); };
        CHECK(std::abs(p.right[size_t(1 + j)].real() - e * op(double(j) / n)) < 1e-12);
        CHECK(std::abs(p.right[size_t(1 + n + j)].real() - f * op((j + 0.5) / n)) < 1e-12);
      }
    }
  }
}

TEST_CASE("spectrum: C2PS scales RTS's eigencoefficients by lambda_k^m (Lemma 5) and meets lambda_k^m v_k up to O(8^-m) (30)") {
  for (int n : {5, 6, 9}) {
    CAPTURE(n);
    const std::vector<C2psScalingStep> steps = c2psEigencoefficientScaling(n, 9);
    REQUIRE(steps.size() == 9);
    for (const C2psScalingStep& s : steps) {
      CAPTURE(s.m);
      CHECK(s.valence == n << s.m);
      CHECK(s.coefficientError < 1e-12);   // Lemma 5, exactly (with (27) corrected)
      CHECK(s.deviationLinks01 < 1e-12);   // (30): the O(8^-m) term is 0 on links 0, 1 ...
      CHECK(s.deviation > 1e-12);          // ... and not beyond (C2PS is not RTS)
    }
    // ... where it shrinks by 8 a step in the end (m = 7..9: between 7 and 8.5).
    for (size_t m = 7; m < steps.size(); ++m) {
      const double ratio = steps[m - 1].deviation / steps[m].deviation;
      CHECK(ratio > 7.0);
      CHECK(ratio < 8.5);
    }
  }
}
