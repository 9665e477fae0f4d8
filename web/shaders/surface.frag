#version 300 es
// Surface colouring of the page: the desktop's shaders/patch.frag for triangles (same colour maps
// and lighting, included from shaders/common; same light lines). SHADING_MODE is
// ShadingParams::Mode: 0 shaded, 1 Gaussian, 2 mean, 3 highlight, 4 reflection.
#include "common/colormap.glsl"
#include "common/lighting.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec2 v_curvature;

out vec4 o_color;

#ifndef SHADING_MODE
#define SHADING_MODE 0
#endif

uniform int u_colormap;
uniform float u_rangeLow;
uniform float u_rangeHigh;
uniform float u_curvatureLighting;
uniform vec3 u_eye;
uniform vec3 u_keyLight;
uniform vec3 u_surfaceColor;
uniform vec3 u_lineDirection;
uniform vec3 u_lineAcross;
uniform vec3 u_planeNormal;
uniform vec3 u_planePoint;
uniform float u_lineSpacing;
uniform float u_lineWidth;

// The desktop's stripeMask, highlightStripe and reflectionStripe (shaders/patch.frag).
float stripeMask(float s, float w) {
  float distanceToLine = abs(fract(s + 0.5) - 0.5);
  float aa = max(fwidth(s), 1e-5);
  float mask = 1.0 - smoothstep(0.5 * w - aa, 0.5 * w + aa, distanceToLine);
  return mix(mask, w, smoothstep(0.2, 0.45, aa));
}

float highlightStripe(vec3 P, vec3 N) {
  float facing = dot(N, u_planeNormal);
  float safeFacing = abs(facing) < 1e-4 ? (facing < 0.0 ? -1e-4 : 1e-4) : facing;
  float mu = dot(u_planePoint - P, u_planeNormal) / safeFacing;
  vec3 H = P + mu * N;
  return stripeMask(dot(H - u_planePoint, u_lineAcross) / u_lineSpacing, u_lineWidth);
}

float reflectionStripe(vec3 toEye, vec3 N) {
  vec3 R = reflect(-toEye, N);
  float angle = atan(dot(R, u_lineAcross), dot(R, u_planeNormal)) / 6.28318530717958647692;
  return stripeMask(angle / u_lineSpacing, u_lineWidth);
}

void main() {
  vec3 P = v_position;
  vec3 toEye = normalize(-P);
  vec3 N = normalize(v_normal);
  vec3 n = facingNormal(N, toEye);
  vec2 light = lightSurface(n, toEye, u_keyLight);

#if SHADING_MODE == 1 || SHADING_MODE == 2
  float value = SHADING_MODE == 1 ? v_curvature.x : v_curvature.y;
  vec3 base = curvatureColor(u_colormap, value, u_rangeLow, u_rangeHigh);
  vec3 color = mix(base, base * light.x + vec3(light.y), u_curvatureLighting);
#elif SHADING_MODE == 3
  vec3 color = mix(u_surfaceColor * light.x + vec3(light.y), vec3(0.05), highlightStripe(P + u_eye, N));
#elif SHADING_MODE == 4
  vec3 color = mix(u_surfaceColor * light.x + vec3(light.y), vec3(0.05), reflectionStripe(toEye, n));
#else
  vec3 color = u_surfaceColor * light.x + vec3(light.y);
#endif
  o_color = vec4(clamp(color, 0.0, 1.0), 1.0);
}
