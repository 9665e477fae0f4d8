// Evaluation of the patches of patch.h: uniform bicubic B-spline patches and the pole's Taylor cap.
// Written as plain arithmetic over fixed-size arrays so that shaders/common/patch_eval.glsl can be
// its mirror image (same function names, same steps); a test compares the two.
#include <cmath>

#include <glm/geometric.hpp>

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

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Uniform cubic B-spline basis on the middle knot span, with first and second derivatives
// (SCHEMES.md section 7).
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

// Normal, K and H from first and second derivatives in any regular parametrisation (section 7).
// A degenerate tangent frame leaves the normal zero and K = H = 0.
void computeCurvature(const Point& xu, const Point& xv, const Point& xuu, const Point& xuv, const Point& xvv,
                      SurfacePoint& sp) {
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
  sp.gaussian = (L * N2 - M * M) / det;
  sp.mean = (E * N2 - 2.0 * F * M + G * L) / (2.0 * det);
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

// PoleCap (patch.h): T(x,y) + u^3 (C(v) - T(R c, R s)), differentiated exactly in the Cartesian
// parameters (x,y) = r (cos 2 pi tau, sin 2 pi tau), which are regular at the pole (u = 0) where
// (u,v) is not. Normal, K, H come from the (x,y) derivatives; du..dvv are converted to (u,v).
SurfacePoint evaluatePoleCap(const Patch& patch, double u, double v) {
  const Point& p0 = patch.cp[0];
  const Point& p1 = patch.cp[1];
  const Point& p2 = patch.cp[2];
  const bool quadratic = patch.cp[11].x > 1.5;  // taylorOrder 2; order 1 keeps the tangent plane only
  const Point p3 = quadratic ? patch.cp[3] : Point(0.0);
  const Point p4 = quadratic ? patch.cp[4] : Point(0.0);
  const Point p5 = quadratic ? patch.cp[5] : Point(0.0);
  const double tau0 = patch.cp[10].x, dtau = patch.cp[10].y, R = patch.cp[10].z;

  // Angle and Cartesian parameters of (u,v).
  const double theta = kTwoPi * (tau0 + dtau * v);
  const double c = std::cos(theta), s = std::sin(theta);
  const double r = R * u, x = r * c, y = r * s;

  // Boundary B-spline C(v) and its theta-derivatives (d theta / d v = 2 pi dtau).
  double bv[4], dbv[4], ddbv[4];
  bsplineBasis(v, bv, dbv, ddbv);
  Point C(0.0), Cv(0.0), Cvv(0.0);
  for (int k = 0; k < 4; ++k) {
    C += bv[k] * patch.cp[6 + k];
    Cv += dbv[k] * patch.cp[6 + k];
    Cvv += ddbv[k] * patch.cp[6 + k];
  }
  const double vPerTheta = 1.0 / (kTwoPi * dtau);

  // Taylor expansion on the circle r = R: T(Rc, Rs) = p0 + R (p1 c + p2 s) + R^2 (p3 + p4 c2 + p5 s2).
  const double c2 = std::cos(2.0 * theta), s2 = std::sin(2.0 * theta);
  const Point Tcircle = p0 + R * (p1 * c + p2 * s) + R * R * (p3 + p4 * c2 + p5 * s2);
  const Point TcircleT = R * (p2 * c - p1 * s) + 2.0 * R * R * (p5 * c2 - p4 * s2);
  const Point TcircleTT = -R * (p1 * c + p2 * s) - 4.0 * R * R * (p4 * c2 + p5 * s2);

  // h(theta) = C - T on the circle; the blend is f = (r/R)^3 h(theta).
  const Point h = C - Tcircle;
  const Point hT = Cv * vPerTheta - TcircleT;
  const Point hTT = Cvv * (vPerTheta * vPerTheta) - TcircleTT;

  // Cartesian derivatives of f (polar chain rule with g(r) = r^3 / R^3, divisions by r cancelled).
  const double k = 1.0 / (R * R * R);
  const Point fx = (k * r * r) * (3.0 * c * h - s * hT);
  const Point fy = (k * r * r) * (3.0 * s * h + c * hT);
  const Point fxx = (k * r) * ((6.0 * c * c + 3.0 * s * s) * h - 4.0 * c * s * hT + s * s * hTT);
  const Point fyy = (k * r) * ((6.0 * s * s + 3.0 * c * c) * h + 4.0 * c * s * hT + c * c * hTT);
  const Point fxy = (k * r) * (c * s * (3.0 * h - hTT) + 2.0 * (c * c - s * s) * hT);

  // Taylor part (32) and its derivatives.
  const Point T = p0 + p1 * x + p2 * y + p3 * (x * x + y * y) + p4 * (x * x - y * y) + p5 * (2.0 * x * y);
  const Point Px = p1 + 2.0 * x * (p3 + p4) + 2.0 * y * p5 + fx;
  const Point Py = p2 + 2.0 * y * (p3 - p4) + 2.0 * x * p5 + fy;
  const Point Pxx = 2.0 * (p3 + p4) + fxx;
  const Point Pyy = 2.0 * (p3 - p4) + fyy;
  const Point Pxy = 2.0 * p5 + fxy;

  SurfacePoint sp;
  sp.position = T + (u * u * u) * h;
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
  if (patch.kind == PatchKind::PoleCap) return evaluatePoleCap(patch, u, v);
  return evaluateBSplinePatch(patch, u, v);
}

}  // namespace polarview
