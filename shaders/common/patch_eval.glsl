// Bicubic patch evaluation: the GPU mirror of polarview::evaluatePatch
// (src/core/spline/bicubic_patch.cpp). Control-point order and the PoleCap layout are documented
// once, in src/core/spline/patch.h: cp[4*j + i], i along u, j along v; PoleCap cp[0..5] = p0..p5,
// cp[6..9] = boundary B-spline b_{j-1..j+2}, cp[10] = (tau0, dtau, R), cp[11] = (taylorOrder,0,0).
// Positions arrive relative to the model centre; p1..p5 and cp[10], cp[11] are not shifted.

const int kPatchRegular = 0;
const int kPatchBoundary = 1;
const int kPatchPolarRing = 2;
const int kPatchPoleCap = 3;
const int kPatchEndCap = 4;
const float kTwoPi = 6.28318530717958647692;

// Differential quantities at one parameter, as polarview::SurfacePoint. For a PoleCap the
// derivatives du..dvv are taken with respect to the Cartesian (x, y) of the Taylor expansion (32)
// (so they stay regular at the pole); position, normal, gaussian and mean are the same either way.
struct SurfacePoint {
  vec3 position, du, dv, duu, duv, dvv;
  vec3 normal;     // unit, along du x dv
  float gaussian;  // K
  float mean;      // H, positive where the surface bends towards the normal
};

// Uniform cubic B-spline basis and its first and second derivatives (SCHEMES.md section 7).
void bsplineBasis(float t, out vec4 b, out vec4 d, out vec4 dd) {
  float s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b = vec4(s * s * s, 3.0 * t3 - 6.0 * t2 + 4.0, -3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0, t3) / 6.0;
  d = vec4(-s * s, 3.0 * t2 - 4.0 * t, -3.0 * t2 + 2.0 * t + 1.0, t2) * 0.5;
  dd = vec4(s, 3.0 * t - 2.0, -3.0 * t + 1.0, t);
}

// Normal, K and H from the first and second derivatives (SCHEMES.md section 7). EG - F^2 is
// computed as |du x dv|^2 (Lagrange's identity), which loses less precision in float.
void computeCurvature(inout SurfacePoint s) {
  vec3 cross_ = cross(s.du, s.dv);
  float area2 = dot(cross_, cross_);
  if (area2 <= 0.0) {
    s.normal = vec3(0.0);
    s.gaussian = 0.0;
    s.mean = 0.0;
    return;
  }
  s.normal = cross_ * inversesqrt(area2);
  float E = dot(s.du, s.du), F = dot(s.du, s.dv), G = dot(s.dv, s.dv);
  float L = dot(s.duu, s.normal), M = dot(s.duv, s.normal), N2 = dot(s.dvv, s.normal);
  s.gaussian = (L * N2 - M * M) / area2;
  s.mean = (E * N2 - 2.0 * F * M + G * L) / (2.0 * area2);
}

// Tensor-product uniform bicubic B-spline over the middle knot span (u,v) in [0,1]^2.
SurfacePoint evaluateBSplinePatch(vec3 cp[16], float u, float v) {
  vec4 bu, du, duu, bv, dv, dvv;
  bsplineBasis(u, bu, du, duu);
  bsplineBasis(v, bv, dv, dvv);
  SurfacePoint s;
  s.position = s.du = s.dv = s.duu = s.duv = s.dvv = vec3(0.0);
  for (int j = 0; j < 4; ++j) {
    // Row j combined along u first: one pass gives the value and both u-derivatives.
    vec3 row = bu[0] * cp[4 * j] + bu[1] * cp[4 * j + 1] + bu[2] * cp[4 * j + 2] + bu[3] * cp[4 * j + 3];
    vec3 rowU = du[0] * cp[4 * j] + du[1] * cp[4 * j + 1] + du[2] * cp[4 * j + 2] + du[3] * cp[4 * j + 3];
    vec3 rowUU = duu[0] * cp[4 * j] + duu[1] * cp[4 * j + 1] + duu[2] * cp[4 * j + 2] + duu[3] * cp[4 * j + 3];
    s.position += bv[j] * row;
    s.du += bv[j] * rowU;
    s.dv += dv[j] * row;
    s.duu += bv[j] * rowUU;
    s.duv += dv[j] * rowU;
    s.dvv += dvv[j] * row;
  }
  computeCurvature(s);
  return s;
}

// Taylor expansion (32): T(x,y) = p0 + p1 x + p2 y + p3 (x^2+y^2) + p4 (x^2-y^2) + 2 p5 x y.
vec3 taylorValue(vec3 cp[16], float x, float y) {
  return cp[0] + cp[1] * x + cp[2] * y + cp[3] * (x * x + y * y) + cp[4] * (x * x - y * y) +
         cp[5] * (2.0 * x * y);
}

// PoleCap (patch.h): X = T(x,y) + u^3 (C(v) - T(R cos, R sin)), u = r/R, tau = tau0 + dtau v.
// The blend D = (r/R)^3 g(theta) is homogeneous of degree 3 in r, so its Cartesian derivatives are
// r^2 (...) and r (...) with no division by r: exact at the pole.
SurfacePoint evaluatePoleCap(vec3 cp[16], float u, float v) {
  float tau0 = cp[10].x, dtau = cp[10].y, R = cp[10].z;
  // BPS caps keep only the tangent plane (taylorOrder 1).
  if (cp[11].x < 1.5) cp[3] = cp[4] = cp[5] = vec3(0.0);
  float theta = kTwoPi * (tau0 + dtau * v);
  float c = cos(theta), s = sin(theta), r = u * R;
  float x = r * c, y = r * s;

  // Boundary curve C(v) and its theta-derivatives (dv/dtheta = 1 / (2 pi dtau)).
  vec4 bv, dbv, ddbv;
  bsplineBasis(v, bv, dbv, ddbv);
  float dvdtheta = 1.0 / (kTwoPi * dtau);
  vec3 C = bv[0] * cp[6] + bv[1] * cp[7] + bv[2] * cp[8] + bv[3] * cp[9];
  vec3 Ct = (dbv[0] * cp[6] + dbv[1] * cp[7] + dbv[2] * cp[8] + dbv[3] * cp[9]) * dvdtheta;
  vec3 Ctt = (ddbv[0] * cp[6] + ddbv[1] * cp[7] + ddbv[2] * cp[8] + ddbv[3] * cp[9]) *
             (dvdtheta * dvdtheta);

  // Taylor polynomial on the circle r = R and its theta-derivatives.
  float c2 = c * c - s * s, s2 = 2.0 * s * c;
  vec3 Tb = cp[0] + R * (c * cp[1] + s * cp[2]) + R * R * (cp[3] + c2 * cp[4] + s2 * cp[5]);
  vec3 Tbt = R * (-s * cp[1] + c * cp[2]) + 2.0 * R * R * (-s2 * cp[4] + c2 * cp[5]);
  vec3 Tbtt = -R * (c * cp[1] + s * cp[2]) - 4.0 * R * R * (c2 * cp[4] + s2 * cp[5]);

  // h(theta) = (C - Tb) / R^3, D = r^3 h.
  float invR3 = 1.0 / (R * R * R);
  vec3 h = (C - Tb) * invR3, ht = (Ct - Tbt) * invR3, htt = (Ctt - Tbtt) * invR3;

  SurfacePoint sp;
  sp.position = taylorValue(cp, x, y) + r * r * r * h;
  sp.du = cp[1] + 2.0 * x * (cp[3] + cp[4]) + 2.0 * y * cp[5] + r * r * (3.0 * c * h - s * ht);
  sp.dv = cp[2] + 2.0 * y * (cp[3] - cp[4]) + 2.0 * x * cp[5] + r * r * (3.0 * s * h + c * ht);
  sp.duu = 2.0 * (cp[3] + cp[4]) + r * ((6.0 * c * c + 3.0 * s * s) * h - 4.0 * s * c * ht + s * s * htt);
  sp.dvv = 2.0 * (cp[3] - cp[4]) + r * ((6.0 * s * s + 3.0 * c * c) * h + 4.0 * s * c * ht + c * c * htt);
  sp.duv = 2.0 * cp[5] + r * (3.0 * s * c * h + 2.0 * (c * c - s * s) * ht - s * c * htt);
  computeCurvature(sp);  // x_x x x_y has the orientation of x_u x x_v (dtau > 0)
  return sp;
}

// Position, derivatives, normal, K and H of any patch kind. [O(1)]
SurfacePoint evaluatePatch(vec3 cp[16], int kind, float u, float v) {
  if (kind == kPatchPoleCap) return evaluatePoleCap(cp, u, v);
  return evaluateBSplinePatch(cp, u, v);
}

// GPU only, for float precision: evaluates relative to a point of the patch (cp[5], or p0 of a
// cap) so that derivatives are differences of small numbers, then moves the position back.
SurfacePoint evaluatePatchLocally(vec3 cp[16], int kind, float u, float v) {
  int originSlot = kind == kPatchPoleCap ? 0 : 5;
  vec3 origin = cp[originSlot];
  for (int k = 0; k < 16; ++k) {
    bool isPosition = kind != kPatchPoleCap || k == 0 || (k >= 6 && k <= 9);
    if (isPosition) cp[k] -= origin;
  }
  SurfacePoint s = evaluatePatch(cp, kind, u, v);
  s.position += origin;
  return s;
}
