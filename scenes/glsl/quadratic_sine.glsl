#version 450
// Animated sine of a quadratic: frequency grows with distance (non-stationary).
vec3 shade(vec2 uv, float time) {
  float q = pow(uv.x, 2.0) + 0.5 * pow(uv.y, 2.0) + 0.3 * uv.x * uv.y;
  float w = 0.5 + 0.5 * sin(q * 2.0 - time * 3.0);
  float w2 = 0.5 + 0.5 * cos(uv.x * 3.0 + time);
  return vec3(w, 0.6 * w + 0.4 * w2, 1.0 - w);
}
