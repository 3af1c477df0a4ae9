#version 450
// Colourful zigzag: stripes along a triangle-wave-displaced coordinate, two colour pairs.
vec3 shade(vec2 uv, float time) {
  float y = uv.y + 0.5 * triangle(uv.x * 2.0);
  float band = square(y * 2.0);
  float hue = square(y * 0.5);
  vec3 a = mix(vec3(0.95, 0.8, 0.2), vec3(0.2, 0.6, 0.9), hue);
  vec3 b = mix(vec3(0.6, 0.1, 0.3), vec3(0.1, 0.3, 0.2), hue);
  return mix(b, a, band);
}
