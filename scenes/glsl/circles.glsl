#version 450
// Tiled greyscale circles (Dorn et al. Listing 3).
vec3 shade(vec2 uv, float time) {
  vec2 p = fract(uv * 2.0) - 0.5;
  float c = step(dot(p, p), 0.16);  // 1 inside radius 0.4
  return vec3(0.1 + 0.8 * c);
}
