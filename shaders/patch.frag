#version 410 core
// Surface colouring: lit, Gaussian / mean curvature, highlight lines (Beier & Chen, view
// independent), reflection lines (zebra, view dependent); optional tessellation wireframe.
// SHADING_MODE (a #define from the renderer, one program per mode: no per-pixel branching on
// llvmpipe) is ShadingParams::Mode: 0 shaded, 1 Gaussian, 2 mean, 3 highlight, 4 reflection.
#include "common/colormap.glsl"
#include "common/lighting.glsl"
#include "common/surface_varyings.glsl"

#ifdef WIREFRAME
in SurfaceData { SURFACE_DATA_MEMBERS } gs_out;
#define FRAG_IN gs_out
noperspective in vec3 g_barycentric;
#else
in SurfaceData { SURFACE_DATA_MEMBERS } te_out;
#define FRAG_IN te_out
#endif

out vec4 o_color;

#ifndef SHADING_MODE
#define SHADING_MODE 0
#endif

uniform int u_colormap;
uniform float u_rangeLow;    // the colour range [low, high] (ColourInterval)
uniform float u_rangeHigh;
uniform float u_curvatureLighting;
uniform vec3 u_eye;             // relative to the model centre (highlight lines are placed there)
uniform vec3 u_keyLight;        // unit, world axes
uniform vec3 u_surfaceColor;
// Light lines: direction B, in-plane normal E (stripe coordinate), plane normal W, plane point A0.
uniform vec3 u_lineDirection;
uniform vec3 u_lineAcross;
uniform vec3 u_planeNormal;
uniform vec3 u_planePoint;
uniform float u_lineSpacing;    // model units (highlight), or fraction of a turn (reflection)
uniform float u_lineWidth;      // dark fraction of one spacing
uniform bool u_drawSurface;     // false: wireframe only
uniform vec3 u_wireColor;

// Anti-aliased stripe mask of coordinate s (in spacings): 1 inside the dark band of width w.
float stripeMask(float s, float w) {
  float distanceToLine = abs(fract(s + 0.5) - 0.5);  // 0 on a line, 0.5 midway
  float aa = max(fwidth(s), 1e-5);
  float mask = 1.0 - smoothstep(0.5 * w - aa, 0.5 * w + aa, distanceToLine);
  // Lines closer than ~3 pixels would alias into moire: fade to their average darkness instead.
  return mix(mask, w, smoothstep(0.2, 0.45, aa));
}

// Beier & Chen highlight lines (docs/shading.md): intersect the normal line P + mu N with the
// light plane, H = P + mu* N, s = ((H - A0) . E) / spacing.
float highlightStripe(vec3 P, vec3 N) {
  float facing = dot(N, u_planeNormal);
  // Normal lines parallel to the plane meet it at infinity: clamp to a far but finite point.
  float safeFacing = abs(facing) < 1e-4 ? (facing < 0.0 ? -1e-4 : 1e-4) : facing;
  float mu = dot(u_planePoint - P, u_planeNormal) / safeFacing;
  vec3 H = P + mu * N;
  return stripeMask(dot(H - u_planePoint, u_lineAcross) / u_lineSpacing, u_lineWidth);
}

// Reflection lines: the reflected view ray's angle around the line direction, in stripes.
float reflectionStripe(vec3 toEye, vec3 N) {
  vec3 R = reflect(-toEye, N);
  float angle = atan(dot(R, u_lineAcross), dot(R, u_planeNormal)) / 6.28318530717958647692;
  return stripeMask(angle / u_lineSpacing, u_lineWidth);
}

void main() {
  vec3 P = FRAG_IN.position;  // relative to the eye
  vec3 toEye = normalize(-P);
  vec3 N = normalize(FRAG_IN.normal);
  vec3 n = facingNormal(N, toEye);
  vec2 light = lightSurface(n, toEye, u_keyLight);

#if SHADING_MODE == 1 || SHADING_MODE == 2
  float value = SHADING_MODE == 1 ? FRAG_IN.curvature.x : FRAG_IN.curvature.y;
  vec3 base = curvatureColor(u_colormap, value, u_rangeLow, u_rangeHigh);
  vec3 color = mix(base, base * light.x + vec3(light.y), u_curvatureLighting);
#elif SHADING_MODE == 3
  vec3 color = mix(u_surfaceColor * light.x + vec3(light.y), vec3(0.05), highlightStripe(P + u_eye, N));
#elif SHADING_MODE == 4
  vec3 color = mix(u_surfaceColor * light.x + vec3(light.y), vec3(0.05), reflectionStripe(toEye, n));
#else
  vec3 color = u_surfaceColor * light.x + vec3(light.y);
#endif

  float alpha = 1.0;
#ifdef WIREFRAME
  float edgeDistance = min(min(g_barycentric.x, g_barycentric.y), g_barycentric.z);
  float wire = 1.0 - smoothstep(0.0, 1.5 * fwidth(edgeDistance), edgeDistance);
  if (!u_drawSurface) {
    if (wire < 0.05) discard;
    color = u_wireColor;
  } else {
    color = mix(color, u_wireColor, 0.8 * wire);
  }
#endif
  o_color = vec4(clamp(color, 0.0, 1.0), alpha);
}
