#version 450
// A log-polar spiral of stripes: angle plus log radius, the classic "droste" stripe.
vec3 shade(vec2 uv, float time) {
  vec2 p = uv - vec2(1.0, 1.0);
  float r = length(p) + 1e-3;
  float a = atan(p.y, p.x);
  float t = fract(a * 3.0 / 6.2831853 + log(r) * 1.5);
  float band = smoothstep(0.45, 0.55, t) - smoothstep(0.9, 1.0, t);
  return mix(vec3(0.1, 0.3, 0.5), vec3(1.0, 0.9, 0.6), band);
}
