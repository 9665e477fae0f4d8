// Bicubic patch evaluation: the GPU mirror of polarview::evaluatePatch
// (src/core/spline/bicubic_patch.cpp). Control-point order and the PoleCap layout are documented
// once, in src/core/spline/patch.h: cp[4*j + i], i along u, j along v; PoleCap cp[0..5] = p0..p5,
// cp[6..9] = boundary B-spline b_{j-1..j+2}, cp[12..15] = first radial derivative B-spline
// e_{j-1..j+2}, and the second radial derivative B-spline f_{j-1..j+2} (patch.h: cp[10], cp[11],
// capExtra) comes as a separate `second[4]` (patch_frame.glsl, fetchCapSecond).
// The renderer uploads each patch in a GPU form (patch_renderer.cpp, "Precision") that these
// functions evaluate with the same steps: in the patch's own frame (positions moved and rotated,
// vectors rotated), B-spline control points as forward differences (c0, D c0, D^2 c0, D^3 c0) along
// each direction (a patch: cp[4 b + a] = D_u^a D_v^b c_00; a cap: cp[6..9], cp[12..15] and second),
// and a cap's sector starting at angle 0 (tau0 = 0, p1 p2 and p4 p5 turned to match; its GPU form
// holds (0, dtau, R) in cp[10], nothing in cp[11]).

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

// Uniform cubic B-spline basis (docs/patches.md) for control points given as forward differences
// (c0, D c0, D^2 c0, D^3 c0; docs/shading.md, Precision at depth), with first and second
// derivatives: the B-spline basis summed as c_i = sum_a binomial(i, a) D^a c0, i.e. sum over
// i >= a of binomial(i, a) B_i(t): (1, t + 1, (3t^2 + 3t + 1) / 6, t^3 / 6). A k-th derivative
// uses differences of order >= k only.
void bsplineBasis(float t, out vec4 b, out vec4 d, out vec4 dd) {
  b = vec4(1.0, t + 1.0, ((3.0 * t + 3.0) * t + 1.0) / 6.0, t * t * t / 6.0);
  d = vec4(0.0, 1.0, t + 0.5, 0.5 * t * t);
  dd = vec4(0.0, 0.0, 1.0, t);
}

// Normal, K and H from the first and second derivatives (docs/shading.md, Curvature). EG - F^2 is
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

// Tensor-product uniform bicubic B-spline over the middle knot span (u,v) in [0,1]^2 (cp: the
// forward-difference table D_u^a D_v^b c_00 at cp[4 b + a]).
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

// Adds the Cartesian derivatives of a blend term r^k F(theta), (x,y) = r (cos, sin), k = 3, 4, 5 (as
// addHomogeneousTerm in bicubic_patch.cpp): every term carries r^(k-1) or r^(k-2), no division.
void addHomogeneousTerm(float k, float r, float c, float s, vec3 F, vec3 Ft, vec3 Ftt,
                        inout SurfacePoint sp) {
  float r2 = k > 4.5 ? r * r * r : k > 3.5 ? r * r : r, r1 = r2 * r;
  sp.du += r1 * (k * c * F - s * Ft);
  sp.dv += r1 * (k * s * F + c * Ft);
  sp.duu += r2 * ((k * (k - 1.0) * c * c + k * s * s) * F - 2.0 * (k - 1.0) * c * s * Ft + s * s * Ftt);
  sp.dvv += r2 * ((k * (k - 1.0) * s * s + k * c * c) * F + 2.0 * (k - 1.0) * c * s * Ft + c * c * Ftt);
  sp.duv += r2 * (k * (k - 2.0) * c * s * F + (k - 1.0) * (c * c - s * s) * Ft - c * s * Ftt);
}

// PoleCap (patch.h): X = T(x,y) + h(u) D0(v) + R g(u) D1(v) + R^2 k(u) D2(v), u = r/R,
// tau = tau0 + dtau v, with the quintic blends h = u^3 (6u^2 - 15u + 10), g = -u^3 (u - 1)(3u - 4),
// k = u^3 (u - 1)^2 / 2. The blend is r^3 A(theta) + r^4 B(theta) + r^5 C(theta), homogeneous in r,
// so its Cartesian derivatives need no division by r: exact at the pole.
SurfacePoint evaluatePoleCap(vec3 cp[16], vec3 second[4], float u, float v) {
  float tau0 = cp[10].x, dtau = cp[10].y, R = cp[10].z;
  float theta = kTwoPi * (tau0 + dtau * v);
  float c = cos(theta), s = sin(theta), r = u * R;
  float x = r * c, y = r * s;

  // Boundary curve C(v), first and second radial derivatives E(v), F(v) and their
  // theta-derivatives (dv/dtheta = 1 / (2 pi dtau)).
  vec4 bv, dbv, ddbv;
  bsplineBasis(v, bv, dbv, ddbv);
  float dvdtheta = 1.0 / (kTwoPi * dtau), dvdtheta2 = dvdtheta * dvdtheta;
  vec3 C = bv[0] * cp[6] + bv[1] * cp[7] + bv[2] * cp[8] + bv[3] * cp[9];
  vec3 Ct = (dbv[0] * cp[6] + dbv[1] * cp[7] + dbv[2] * cp[8] + dbv[3] * cp[9]) * dvdtheta;
  vec3 Ctt = (ddbv[0] * cp[6] + ddbv[1] * cp[7] + ddbv[2] * cp[8] + ddbv[3] * cp[9]) * dvdtheta2;
  vec3 E = bv[0] * cp[12] + bv[1] * cp[13] + bv[2] * cp[14] + bv[3] * cp[15];
  vec3 Et = (dbv[0] * cp[12] + dbv[1] * cp[13] + dbv[2] * cp[14] + dbv[3] * cp[15]) * dvdtheta;
  vec3 Ett = (ddbv[0] * cp[12] + ddbv[1] * cp[13] + ddbv[2] * cp[14] + ddbv[3] * cp[15]) * dvdtheta2;
  vec3 F = bv[0] * second[0] + bv[1] * second[1] + bv[2] * second[2] + bv[3] * second[3];
  vec3 Ft = (dbv[0] * second[0] + dbv[1] * second[1] + dbv[2] * second[2] + dbv[3] * second[3]) * dvdtheta;
  vec3 Ftt = (ddbv[0] * second[0] + ddbv[1] * second[1] + ddbv[2] * second[2] + ddbv[3] * second[3]) * dvdtheta2;

  // Taylor polynomial on the circle r = R and its first and second radial derivatives there, with
  // theta-derivatives: Q = p3 + c2 p4 + s2 p5, L = c p1 + s p2.
  float c2 = c * c - s * s, s2 = 2.0 * s * c;
  vec3 Q = cp[3] + c2 * cp[4] + s2 * cp[5], Qt = 2.0 * (-s2 * cp[4] + c2 * cp[5]), Qtt = -4.0 * (c2 * cp[4] + s2 * cp[5]);
  vec3 L = c * cp[1] + s * cp[2], Lt = -s * cp[1] + c * cp[2];
  vec3 Tb = cp[0] + R * L + R * R * Q, Tbt = R * Lt + R * R * Qt, Tbtt = -R * L + R * R * Qtt;
  vec3 Tr = L + 2.0 * R * Q, Trt = Lt + 2.0 * R * Qt, Trtt = -L + 2.0 * R * Qtt;

  // Mismatches D0 (position), D1 (first), D2 (second radial derivative); the r^3, r^4, r^5
  // coefficients A = (10 D0 - 4R D1 + R^2/2 D2) / R^3, B = (-15 D0 + 7R D1 - R^2 D2) / R^4,
  // C = (6 D0 - 3R D1 + R^2/2 D2) / R^5.
  vec3 D0 = C - Tb, D0t = Ct - Tbt, D0tt = Ctt - Tbtt;
  vec3 D1 = (E - Tr) * R, D1t = (Et - Trt) * R, D1tt = (Ett - Trtt) * R;
  vec3 D2 = (F - 2.0 * Q) * (R * R), D2t = (Ft - 2.0 * Qt) * (R * R), D2tt = (Ftt - 2.0 * Qtt) * (R * R);
  float iR = 1.0 / R, iR3 = iR * iR * iR, iR4 = iR3 * iR, iR5 = iR4 * iR;

  SurfacePoint sp;
  float u3 = u * u * u;
  float h = u3 * ((6.0 * u - 15.0) * u + 10.0), g = -u3 * (u - 1.0) * (3.0 * u - 4.0), k = 0.5 * u3 * (u - 1.0) * (u - 1.0);
  sp.position = taylorValue(cp, x, y) + h * D0 + g * D1 + k * D2;
  sp.du = cp[1] + 2.0 * x * (cp[3] + cp[4]) + 2.0 * y * cp[5];
  sp.dv = cp[2] + 2.0 * y * (cp[3] - cp[4]) + 2.0 * x * cp[5];
  sp.duu = 2.0 * (cp[3] + cp[4]);
  sp.dvv = 2.0 * (cp[3] - cp[4]);
  sp.duv = 2.0 * cp[5];
  addHomogeneousTerm(3.0, r, c, s, iR3 * (10.0 * D0 - 4.0 * D1 + 0.5 * D2), iR3 * (10.0 * D0t - 4.0 * D1t + 0.5 * D2t),
                     iR3 * (10.0 * D0tt - 4.0 * D1tt + 0.5 * D2tt), sp);
  addHomogeneousTerm(4.0, r, c, s, iR4 * (-15.0 * D0 + 7.0 * D1 - D2), iR4 * (-15.0 * D0t + 7.0 * D1t - D2t),
                     iR4 * (-15.0 * D0tt + 7.0 * D1tt - D2tt), sp);
  addHomogeneousTerm(5.0, r, c, s, iR5 * (6.0 * D0 - 3.0 * D1 + 0.5 * D2), iR5 * (6.0 * D0t - 3.0 * D1t + 0.5 * D2t),
                     iR5 * (6.0 * D0tt - 3.0 * D1tt + 0.5 * D2tt), sp);
  computeCurvature(sp);  // x_x x x_y has the orientation of x_u x x_v (dtau > 0)
  return sp;
}

// Position, derivatives, normal, K and H of any patch kind. [O(1)]
// `second`: a cap's f_{j-1..j+2} (unused for other kinds).
SurfacePoint evaluatePatch(vec3 cp[16], vec3 second[4], int kind, float u, float v) {
  if (kind == kPatchPoleCap) return evaluatePoleCap(cp, second, u, v);
  return evaluateBSplinePatch(cp, u, v);
}
