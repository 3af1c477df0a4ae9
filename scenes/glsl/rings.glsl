#version 450
// Wood-like rings: concentric bands around an off-centre point, slightly wobbled by a sine,
// with a smooth dark line at each ring boundary.
vec3 shade(vec2 uv, float time) {
  vec2 c = uv - vec2(0.3, -0.2);
  float r = length(c) + 0.05 * sin(6.0 * c.x) * cos(5.0 * c.y);
  float band = fract(r * 3.0);
  float line = smoothstep(0.0, 0.08, band) * smoothstep(1.0, 0.85, band);
  vec3 light = vec3(0.85, 0.65, 0.4), dark = vec3(0.55, 0.35, 0.18);
  vec3 wood = mix(dark, light, band);
  return mix(vec3(0.25, 0.13, 0.05), wood, line);
}
