// Two-sided lighting: a headlight plus a key light, both white, Blinn-Phong highlight.

// Normal turned towards the viewer (the surfaces are open or seen from inside).
vec3 facingNormal(vec3 normal, vec3 toEye) {
  return dot(normal, toEye) < 0.0 ? -normal : normal;
}

// Diffuse factor and specular term of the two lights at a point with normal n (facing the eye).
vec2 lightSurface(vec3 n, vec3 toEye, vec3 keyLight) {
  float headlight = max(dot(n, toEye), 0.0);
  float key = max(dot(n, keyLight), 0.0);
  float diffuse = 0.18 + 0.55 * headlight + 0.35 * key;
  vec3 halfway = normalize(keyLight + toEye);
  // x^48 by squaring: pow() is several times slower on llvmpipe.
  float x = max(dot(n, halfway), 0.0), x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x16 = x8 * x8;
  float specular = 0.25 * x16 * x16 * x16;
  return vec2(diffuse, specular);
}
