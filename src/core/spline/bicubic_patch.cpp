// Evaluation of the patches of patch.h: uniform bicubic B-spline patches and the pole's Taylor cap.
// Written as plain arithmetic over fixed-size arrays so that shaders/common/patch_eval.glsl can be
// its mirror image (same function names, same steps); a test compares the two.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/mesh/constants.h"
#include "core/spline/patch.h"

namespace polarview {

const char* patchKindName(PatchKind kind) {
  switch (kind) {
    case PatchKind::Regular: return "regular";
    case PatchKind::Boundary: return "boundary";
    case PatchKind::PolarRing: return "polar-ring";
    case PatchKind::PoleCap: return "pole-cap";
    case PatchKind::EndCap: return "end-cap";
  }
  return "?";
}

namespace {

// Uniform cubic B-spline basis on the middle knot span, with first and second derivatives
// (docs/patches.md, B-spline basis and Bezier form).
void bsplineBasis(double t, double b[4], double db[4], double ddb[4]) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b[0] = s * s * s / 6.0;
  b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  b[3] = t3 / 6.0;
  db[0] = -0.5 * s * s;
  db[1] = 0.5 * (3.0 * t2 - 4.0 * t);
  db[2] = 0.5 * (-3.0 * t2 + 2.0 * t + 1.0);
  db[3] = 0.5 * t2;
  ddb[0] = s;
  ddb[1] = 3.0 * t - 2.0;
  ddb[2] = -3.0 * t + 1.0;
  ddb[3] = t;
}

// Normal, K and H from first and second derivatives in any regular parametrisation (docs/shading.md,
// Curvature). The derivatives are first scaled by a power of two (exact) to a first derivative of
// size 1..2, so E G - F^2 (fourth powers) neither underflows nor overflows: models of 1e-150 and
// 1e150 get their K (1e300, 1e-300) as a model of 1 does; K and H are scaled back.
// A degenerate tangent frame leaves the normal zero and K = H = 0.
void computeCurvature(const Point& xuIn, const Point& xvIn, const Point& xuuIn, const Point& xuvIn, const Point& xvvIn,
                      SurfacePoint& sp) {
  const double largest = std::max({std::abs(xuIn.x), std::abs(xuIn.y), std::abs(xuIn.z), std::abs(xvIn.x),
                                   std::abs(xvIn.y), std::abs(xvIn.z)});
  if (!(largest > 0.0) || !std::isfinite(largest)) {
    sp.normal = Point(0.0);
    sp.gaussian = sp.mean = 0.0;
    return;
  }
  const int exponent = std::ilogb(largest);
  const Point xu = std::ldexp(1.0, -exponent) * xuIn, xv = std::ldexp(1.0, -exponent) * xvIn;
  const Point xuu = std::ldexp(1.0, -exponent) * xuuIn, xuv = std::ldexp(1.0, -exponent) * xuvIn,
              xvv = std::ldexp(1.0, -exponent) * xvvIn;
  const Point cross = glm::cross(xu, xv);
  const double crossLength = glm::length(cross);
  const double E = glm::dot(xu, xu), F = glm::dot(xu, xv), G = glm::dot(xv, xv);
  const double det = E * G - F * F;
  if (!(crossLength > 0.0) || !(det > 1e-300)) {
    sp.normal = Point(0.0);
    sp.gaussian = sp.mean = 0.0;
    return;
  }
  sp.normal = cross / crossLength;
  const double L = glm::dot(xuu, sp.normal), M = glm::dot(xuv, sp.normal), N2 = glm::dot(xvv, sp.normal);
  // In the scaled derivatives K' = K s^2 and H' = H s for s = 2^exponent.
  sp.gaussian = std::ldexp((L * N2 - M * M) / det, -2 * exponent);
  sp.mean = std::ldexp((E * N2 - 2.0 * F * M + G * L) / (2.0 * det), -exponent);
  // A feature of 1e-300 in a model of size 1 has K ~ 1e600: past double's range, taken as the
  // degenerate frame it nearly is (what the unscaled 1e-300 floor gave before).
  if (!std::isfinite(sp.gaussian) || !std::isfinite(sp.mean)) sp.gaussian = sp.mean = 0.0;
}

// Tensor-product B-spline patch: position and derivatives over the middle knot span.
SurfacePoint evaluateBSplinePatch(const Patch& patch, double u, double v) {
  double bu[4], dbu[4], ddbu[4], bv[4], dbv[4], ddbv[4];
  bsplineBasis(u, bu, dbu, ddbu);
  bsplineBasis(v, bv, dbv, ddbv);
  SurfacePoint sp;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const Point& c = patch.cp[4 * j + i];
      sp.position += (bu[i] * bv[j]) * c;
      sp.du += (dbu[i] * bv[j]) * c;
      sp.dv += (bu[i] * dbv[j]) * c;
      sp.duu += (ddbu[i] * bv[j]) * c;
      sp.duv += (dbu[i] * dbv[j]) * c;
      sp.dvv += (bu[i] * ddbv[j]) * c;
    }
  }
  computeCurvature(sp.du, sp.dv, sp.duu, sp.duv, sp.dvv, sp);
  return sp;
}

// Cartesian derivatives of a blend term r^k F(theta) ((x,y) = r (cos, sin)), added to the sums.
// Homogeneous of degree k >= 3, so every term carries r^(k-1) or r^(k-2): no division by r.
struct CartesianDerivatives {
  Point x{}, y{}, xx{}, xy{}, yy{};
};
void addHomogeneousTerm(int k, double r, double c, double s, const Point& F, const Point& Ft, const Point& Ftt,
                        CartesianDerivatives& d) {
  double r2 = 1.0;
  for (int e = 0; e < k - 2; ++e) r2 *= r;
  const double kd = double(k), r1 = r2 * r;
  d.x += r1 * (kd * c * F - s * Ft);
  d.y += r1 * (kd * s * F + c * Ft);
  d.xx += r2 * ((kd * (kd - 1.0) * c * c + kd * s * s) * F - 2.0 * (kd - 1.0) * c * s * Ft + s * s * Ftt);
  d.yy += r2 * ((kd * (kd - 1.0) * s * s + kd * c * c) * F + 2.0 * (kd - 1.0) * c * s * Ft + c * c * Ftt);
  d.xy += r2 * (kd * (kd - 2.0) * c * s * F + (kd - 1.0) * (c * c - s * s) * Ft - c * s * Ftt);
}

// PoleCap (patch.h): T(x,y) + h(u) D0(v) + R g(u) D1(v) + R^2 k(u) D2(v), differentiated exactly in
// the Cartesian parameters (x,y) = r (cos 2 pi tau, sin 2 pi tau), which are regular at the pole
// (u = 0) where (u,v) is not. Normal, K, H come from the (x,y) derivatives; du..dvv are converted
// to (u,v).
SurfacePoint evaluatePoleCap(const Patch& patch, double u, double v) {
  const Point& p0 = patch.cp[0];
  const Point& p1 = patch.cp[1];
  const Point& p2 = patch.cp[2];
  const Point& p3 = patch.cp[3];
  const Point& p4 = patch.cp[4];
  const Point& p5 = patch.cp[5];
  const double n = double(patch.sectorCount), R = kPoleCapRadius;
  const double tau0 = double(patch.sector) / n, dtau = 1.0 / n;

  // Angle and Cartesian parameters of (u,v).
  const double theta = kTwoPi * (tau0 + dtau * v);
  const double c = std::cos(theta), s = std::sin(theta);
  const double r = R * u, x = r * c, y = r * s;

  // The ring's boundary curve C(v) and its first and second radial derivatives E(v), F(v) at r = R,
  // with theta-derivatives (d theta / d v = 2 pi dtau).
  double bv[4], dbv[4], ddbv[4];
  bsplineBasis(v, bv, dbv, ddbv);
  Point C(0.0), Cv(0.0), Cvv(0.0), E(0.0), Ev(0.0), Evv(0.0), F(0.0), Fv(0.0), Fvv(0.0);
  for (int k = 0; k < 4; ++k) {
    C += bv[k] * patch.cp[6 + k];
    Cv += dbv[k] * patch.cp[6 + k];
    Cvv += ddbv[k] * patch.cp[6 + k];
    E += bv[k] * patch.cp[12 + k];
    Ev += dbv[k] * patch.cp[12 + k];
    Evv += ddbv[k] * patch.cp[12 + k];
    const Point& f = capSecondPoint(patch, k);
    F += bv[k] * f;
    Fv += dbv[k] * f;
    Fvv += ddbv[k] * f;
  }
  const double vPerTheta = 1.0 / (kTwoPi * dtau), vPerTheta2 = vPerTheta * vPerTheta;

  // Taylor expansion on the circle r = R and its first and second radial derivatives there, with
  // theta-derivatives: T(Rc, Rs) = p0 + R (p1 c + p2 s) + R^2 Q, dT/dr = p1 c + p2 s + 2R Q,
  // d2T/dr2 = 2 Q, Q = p3 + p4 c2 + p5 s2.
  const double c2 = std::cos(2.0 * theta), s2 = std::sin(2.0 * theta);
  const Point Q = p3 + p4 * c2 + p5 * s2, Qt = 2.0 * (p5 * c2 - p4 * s2), Qtt = -4.0 * (p4 * c2 + p5 * s2);
  const Point L = p1 * c + p2 * s, Lt = p2 * c - p1 * s, Ltt = -L;
  const Point Tcircle = p0 + R * L + R * R * Q, TcircleT = R * Lt + R * R * Qt, TcircleTT = R * Ltt + R * R * Qtt;
  const Point Tr = L + 2.0 * R * Q, TrT = Lt + 2.0 * R * Qt, TrTT = Ltt + 2.0 * R * Qtt;
  const Point Trr = 2.0 * Q, TrrT = 2.0 * Qt, TrrTT = 2.0 * Qtt;

  // Mismatches on the circle: D0 of position, D1 of the first, D2 of the second radial derivative.
  const Point D0 = C - Tcircle, D0t = Cv * vPerTheta - TcircleT, D0tt = Cvv * vPerTheta2 - TcircleTT;
  const Point D1 = E - Tr, D1t = Ev * vPerTheta - TrT, D1tt = Evv * vPerTheta2 - TrTT;
  const Point D2 = F - Trr, D2t = Fv * vPerTheta - TrrT, D2tt = Fvv * vPerTheta2 - TrrTT;

  // h(r/R) D0 + R g(r/R) D1 + R^2 k(r/R) D2 = r^3 A + r^4 B + r^5 C with (h, g, k as polynomials:
  // h = 10u^3 - 15u^4 + 6u^5, g = -4u^3 + 7u^4 - 3u^5, k = (u^3 - 2u^4 + u^5) / 2)
  // A = (10 D0 - 4R D1 + R^2/2 D2) / R^3, B = (-15 D0 + 7R D1 - R^2 D2) / R^4,
  // C = (6 D0 - 3R D1 + R^2/2 D2) / R^5.
  const double iR = 1.0 / R, iR3 = iR * iR * iR, iR4 = iR3 * iR, iR5 = iR4 * iR;
  const auto combine = [&](double w0, double w1, double w2, const Point& d0, const Point& d1, const Point& d2) {
    return w0 * d0 + (w1 * R) * d1 + (w2 * R * R) * d2;
  };
  CartesianDerivatives f;
  const double weights[3][3] = {{10.0, -4.0, 0.5}, {-15.0, 7.0, -1.0}, {6.0, -3.0, 0.5}};
  const double scale[3] = {iR3, iR4, iR5};
  for (int t = 0; t < 3; ++t) {
    const double* w = weights[t];
    addHomogeneousTerm(3 + t, r, c, s, scale[t] * combine(w[0], w[1], w[2], D0, D1, D2),
                       scale[t] * combine(w[0], w[1], w[2], D0t, D1t, D2t), scale[t] * combine(w[0], w[1], w[2], D0tt, D1tt, D2tt), f);
  }

  // Taylor part (32) and its derivatives.
  const Point T = p0 + p1 * x + p2 * y + p3 * (x * x + y * y) + p4 * (x * x - y * y) + p5 * (2.0 * x * y);
  const Point Px = p1 + 2.0 * x * (p3 + p4) + 2.0 * y * p5 + f.x;
  const Point Py = p2 + 2.0 * y * (p3 - p4) + 2.0 * x * p5 + f.y;
  const Point Pxx = 2.0 * (p3 + p4) + f.xx;
  const Point Pyy = 2.0 * (p3 - p4) + f.yy;
  const Point Pxy = 2.0 * p5 + f.xy;

  SurfacePoint sp;
  const double u3 = u * u * u;
  const double h = u3 * ((6.0 * u - 15.0) * u + 10.0), g = -u3 * (u - 1.0) * (3.0 * u - 4.0), k = 0.5 * u3 * (u - 1.0) * (u - 1.0);
  sp.position = T + h * D0 + (R * g) * D1 + (R * R * k) * D2;
  computeCurvature(Px, Py, Pxx, Pxy, Pyy, sp);

  // (u,v) derivatives: u = r/R, theta = 2 pi (tau0 + dtau v).
  const Point Pr = c * Px + s * Py;
  const Point Pt = r * (c * Py - s * Px);
  const Point Prr = c * c * Pxx + 2.0 * c * s * Pxy + s * s * Pyy;
  const Point Prt = (c * Py - s * Px) + r * (c * s * (Pyy - Pxx) + (c * c - s * s) * Pxy);
  const Point Ptt = -r * Pr + r * r * (s * s * Pxx - 2.0 * c * s * Pxy + c * c * Pyy);
  const double thetaPerV = kTwoPi * dtau;
  sp.du = R * Pr;
  sp.dv = thetaPerV * Pt;
  sp.duu = (R * R) * Prr;
  sp.duv = (R * thetaPerV) * Prt;
  sp.dvv = (thetaPerV * thetaPerV) * Ptt;
  return sp;
}

}  // namespace

SurfacePoint evaluatePatch(const Patch& patch, double u, double v) {
  // Evaluated relative to the origin (the derivatives keep the precision of the relative points).
  SurfacePoint sp = patch.kind == PatchKind::PoleCap ? evaluatePoleCap(patch, u, v) : evaluateBSplinePatch(patch, u, v);
  sp.position += patch.origin;
  return sp;
}

bool isPositionPoint(PatchKind kind, int k) {
  if (kind != PatchKind::PoleCap) return k >= 0 && k < 16;
  return k == 0 || (k >= 6 && k <= 9);
}

Patch withAbsolutePositions(const Patch& patch) {
  Patch out = patch;
  for (int k = 0; k < 16; ++k)
    if (isPositionPoint(patch.kind, k)) out.cp[size_t(k)] += patch.origin;
  out.origin = Point(0.0);
  return out;
}

Patch turnedPatch(const Patch& patch, int turns) {
  if (patch.kind == PatchKind::PoleCap) return patch;
  Patch turned = patch;
  for (int k = 0; k < 16; ++k) turned.cp[size_t(k)] = patch.cp[size_t(turnedControlIndex(k, turns))];
  // Edge s (corner s to s + 1) of the turned patch is edge s + turns of the patch.
  for (int s = 0; s < 4; ++s) turned.edgeLevelDelta[size_t(s)] = patch.edgeLevelDelta[size_t((s + turns % 4 + 4) % 4)];
  return turned;
}

void turnedParameter(double* u, double* v, int turns) {
  for (int t = 0; t < ((turns % 4) + 4) % 4; ++t) {
    const double before = *u;
    *u = 1.0 - *v;
    *v = before;
  }
}

}  // namespace polarview
