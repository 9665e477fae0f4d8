// Curvature colour maps. Mirror of polarview::colorMapCpu (src/pipeline/shading.cpp); the render
// tests compare the two. The range is [low, high] (ColourInterval in src/pipeline/shading.h). With
// zero inside it values map to t in [-1, 1] with two slopes, zero in the middle: t = value / high
// above zero and value / -low below. A one-sided range (all values of one sign) spans the half of
// the map of its sign linearly: t = (value - low) / (high - low) in [0, 1], or that minus 1.

const int kColorMapPaper = 0;
const int kColorMapCoolWarm = 1;
const int kColorMapViridis = 2;
const int kColorMapMagnitude = 3;

// Half-width of the paper map's green band, as a fraction of the range.
const float kPaperGreenBand = 0.1;

// The paper's Fig. 13 map: "the green range straddles Gauss zero curvature, while negative
// curvature is blue and positive is red": |t| <= kPaperGreenBand is green, beyond it the hue runs
// on to blue (t = -1) or red (t = 1) through cyan and yellow, saturating beyond the range.
vec3 paperColorMap(float t) {
  float s = sign(t) * max(abs(t) - kPaperGreenBand, 0.0) / (1.0 - kPaperGreenBand);
  float hue = (1.0 - s) * 2.0;  // in units of 60 degrees: 0 red, 2 green, 4 blue
  vec3 rgb = clamp(abs(mod(hue + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return 0.95 * rgb;
}

// Piecewise-linear through five stops at t = 0, 0.25, 0.5, 0.75, 1 (t in [0,1]).
vec3 fiveStopColorMap(float t, vec3 c0, vec3 c1, vec3 c2, vec3 c3, vec3 c4) {
  float x = clamp(t, 0.0, 1.0) * 4.0;
  if (x < 1.0) return mix(c0, c1, x);
  if (x < 2.0) return mix(c1, c2, x - 1.0);
  if (x < 3.0) return mix(c2, c3, x - 2.0);
  return mix(c3, c4, x - 3.0);
}

// Moreland's diverging cool-warm (blue - light grey - red).
vec3 coolWarmColorMap(float t) {
  return fiveStopColorMap(0.5 * (t + 1.0), vec3(0.230, 0.299, 0.754), vec3(0.552, 0.690, 0.996),
                          vec3(0.865, 0.865, 0.865), vec3(0.958, 0.603, 0.482),
                          vec3(0.706, 0.016, 0.150));
}

// Viridis (perceptually uniform, sequential; -range -> dark purple, +range -> yellow).
vec3 viridisColorMap(float t) {
  return fiveStopColorMap(0.5 * (t + 1.0), vec3(0.267, 0.005, 0.329), vec3(0.229, 0.322, 0.546),
                          vec3(0.128, 0.567, 0.551), vec3(0.369, 0.789, 0.383),
                          vec3(0.993, 0.906, 0.144));
}

// The paper's Figs. 11-12 map: dark blue where the value is near zero, through blue, cyan and
// yellow to red at |value| = range (sign ignored).
vec3 magnitudeColorMap(float t) {
  return fiveStopColorMap(abs(t), vec3(0.0, 0.0, 0.45), vec3(0.0, 0.3, 1.0), vec3(0.0, 0.9, 0.9),
                          vec3(1.0, 0.9, 0.0), vec3(0.85, 0.0, 0.0));
}

float curvatureMapT(float value, float low, float high) {
  if (low < 0.0 && high > 0.0) return clamp(value / max(value >= 0.0 ? high : -low, 1e-30), -1.0, 1.0);
  float p = clamp((value - low) / max(high - low, 1e-30), 0.0, 1.0);
  return high > 0.0 ? p : p - 1.0;
}

vec3 curvatureColor(int colormap, float value, float low, float high) {
  float t = curvatureMapT(value, low, high);
  if (colormap == kColorMapMagnitude) return magnitudeColorMap(t);
  if (colormap == kColorMapCoolWarm) return coolWarmColorMap(t);
  if (colormap == kColorMapViridis) return viridisColorMap(t);
  return paperColorMap(t);
}
