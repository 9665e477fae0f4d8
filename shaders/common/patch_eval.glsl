// Bicubic patch evaluation: the GPU mirror of polarview::evaluatePatch
// (src/core/spline/bicubic_patch.cpp). Control-point order and the PoleCap layout are documented
// once, in src/core/spline/patch.h: cp[4*j + i], i along u, j along v; PoleCap cp[0..5] = p0..p5,
// cp[6..9] = boundary B-spline b_{j-1..j+2}, cp[10] = (tau0, dtau, R), cp[11] = (taylorOrder,0,0),
// cp[12..15] = cross-boundary derivative B-spline e_{j-1..j+2}.
// The renderer uploads each patch in a GPU form (patch_renderer.cpp, "Precision") that these
// functions evaluate with the same steps: in the patch's own frame (positions moved and rotated,
// vectors rotated), B-spline control points as forward differences (c0, D c0, D^2 c0, D^3 c0) along
// each direction (a patch: cp[4 b + a] = D_u^a D_v^b c_00; a cap: cp[6..9] and cp[12..15]), and a
// cap's sector starting at angle 0 (tau0 = 0, p1 p2 and p4 p5 turned to match).

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

// Adds the Cartesian derivatives of a blend term r^k F(theta), (x,y) = r (cos, sin), k >= 3 (as
// addHomogeneousTerm in bicubic_patch.cpp): every term carries r^(k-1) or r^(k-2), no division.
void addHomogeneousTerm(float k, float r, float c, float s, vec3 F, vec3 Ft, vec3 Ftt,
                        inout SurfacePoint sp) {
  float r2 = k > 3.5 ? r * r : r, r1 = r2 * r;
  sp.du += r1 * (k * c * F - s * Ft);
  sp.dv += r1 * (k * s * F + c * Ft);
  sp.duu += r2 * ((k * (k - 1.0) * c * c + k * s * s) * F - 2.0 * (k - 1.0) * c * s * Ft + s * s * Ftt);
  sp.dvv += r2 * ((k * (k - 1.0) * s * s + k * c * c) * F + 2.0 * (k - 1.0) * c * s * Ft + c * c * Ftt);
  sp.duv += r2 * (k * (k - 2.0) * c * s * F + (k - 1.0) * (c * c - s * s) * Ft - c * s * Ftt);
}

// PoleCap (patch.h): X = T(x,y) + h(u) D0(v) + R g(u) D1(v), u = r/R, tau = tau0 + dtau v, with
// h = u^3 (4 - 3u), g = u^3 (u - 1). The blend is r^3 A(theta) + r^4 B(theta), homogeneous in r,
// so its Cartesian derivatives need no division by r: exact at the pole.
SurfacePoint evaluatePoleCap(vec3 cp[16], float u, float v) {
  float tau0 = cp[10].x, dtau = cp[10].y, R = cp[10].z;
  // BPS caps keep only the tangent plane (taylorOrder 1).
  if (cp[11].x < 1.5) cp[3] = cp[4] = cp[5] = vec3(0.0);
  float theta = kTwoPi * (tau0 + dtau * v);
  float c = cos(theta), s = sin(theta), r = u * R;
  float x = r * c, y = r * s;

  // Boundary curve C(v), cross-boundary derivative E(v) and their theta-derivatives
  // (dv/dtheta = 1 / (2 pi dtau)).
  vec4 bv, dbv, ddbv;
  bsplineBasis(v, bv, dbv, ddbv);
  float dvdtheta = 1.0 / (kTwoPi * dtau), dvdtheta2 = dvdtheta * dvdtheta;
  vec3 C = bv[0] * cp[6] + bv[1] * cp[7] + bv[2] * cp[8] + bv[3] * cp[9];
  vec3 Ct = (dbv[0] * cp[6] + dbv[1] * cp[7] + dbv[2] * cp[8] + dbv[3] * cp[9]) * dvdtheta;
  vec3 Ctt = (ddbv[0] * cp[6] + ddbv[1] * cp[7] + ddbv[2] * cp[8] + ddbv[3] * cp[9]) * dvdtheta2;
  vec3 E = bv[0] * cp[12] + bv[1] * cp[13] + bv[2] * cp[14] + bv[3] * cp[15];
  vec3 Et = (dbv[0] * cp[12] + dbv[1] * cp[13] + dbv[2] * cp[14] + dbv[3] * cp[15]) * dvdtheta;
  vec3 Ett = (ddbv[0] * cp[12] + ddbv[1] * cp[13] + ddbv[2] * cp[14] + ddbv[3] * cp[15]) * dvdtheta2;

  // Taylor polynomial on the circle r = R, its radial derivative there, and theta-derivatives.
  float c2 = c * c - s * s, s2 = 2.0 * s * c;
  vec3 Tb = cp[0] + R * (c * cp[1] + s * cp[2]) + R * R * (cp[3] + c2 * cp[4] + s2 * cp[5]);
  vec3 Tbt = R * (-s * cp[1] + c * cp[2]) + 2.0 * R * R * (-s2 * cp[4] + c2 * cp[5]);
  vec3 Tbtt = -R * (c * cp[1] + s * cp[2]) - 4.0 * R * R * (c2 * cp[4] + s2 * cp[5]);
  vec3 Tr = c * cp[1] + s * cp[2] + 2.0 * R * (cp[3] + c2 * cp[4] + s2 * cp[5]);
  vec3 Trt = -s * cp[1] + c * cp[2] + 4.0 * R * (-s2 * cp[4] + c2 * cp[5]);
  vec3 Trtt = -(c * cp[1] + s * cp[2]) - 8.0 * R * (c2 * cp[4] + s2 * cp[5]);

  // Mismatches D0 (position) and D1 (radial derivative); A = 4 D0/R^3 - D1/R^2 and
  // B = -3 D0/R^4 + D1/R^3 are the r^3 and r^4 coefficients of the blend.
  vec3 D0 = C - Tb, D0t = Ct - Tbt, D0tt = Ctt - Tbtt;
  vec3 D1 = E - Tr, D1t = Et - Trt, D1tt = Ett - Trtt;
  float iR = 1.0 / R, iR2 = iR * iR, iR3 = iR2 * iR, iR4 = iR3 * iR;

  SurfacePoint sp;
  float h = u * u * u * (4.0 - 3.0 * u), g = u * u * u * (u - 1.0);
  sp.position = taylorValue(cp, x, y) + h * D0 + (R * g) * D1;
  sp.du = cp[1] + 2.0 * x * (cp[3] + cp[4]) + 2.0 * y * cp[5];
  sp.dv = cp[2] + 2.0 * y * (cp[3] - cp[4]) + 2.0 * x * cp[5];
  sp.duu = 2.0 * (cp[3] + cp[4]);
  sp.dvv = 2.0 * (cp[3] - cp[4]);
  sp.duv = 2.0 * cp[5];
  addHomogeneousTerm(3.0, r, c, s, 4.0 * iR3 * D0 - iR2 * D1, 4.0 * iR3 * D0t - iR2 * D1t,
                     4.0 * iR3 * D0tt - iR2 * D1tt, sp);
  addHomogeneousTerm(4.0, r, c, s, -3.0 * iR4 * D0 + iR3 * D1, -3.0 * iR4 * D0t + iR3 * D1t,
                     -3.0 * iR4 * D0tt + iR3 * D1tt, sp);
  computeCurvature(sp);  // x_x x x_y has the orientation of x_u x x_v (dtau > 0)
  return sp;
}

// Position, derivatives, normal, K and H of any patch kind. [O(1)]
SurfacePoint evaluatePatch(vec3 cp[16], int kind, float u, float v) {
  if (kind == kPatchPoleCap) return evaluatePoleCap(cp, u, v);
  return evaluateBSplinePatch(cp, u, v);
}
