#version 450
// Animated diagonal stripes of varying width, crossed by thin stripes the other way.
vec3 shade(vec2 uv, float time) {
  float s = dot(uv, vec2(0.8, 0.6)) * 3.0 + 0.25 * time;
  float width = 0.35 + 0.25 * sin(uv.y * 0.7);  // duty cycle changes slowly across the plane
  float wide = step(fract(s), width);
  float t = dot(uv, vec2(-0.6, 0.8)) * 8.0;
  float thin = 1.0 - step(0.1, fract(t));
  vec3 c = mix(vec3(0.9, 0.9, 0.85), vec3(0.8, 0.2, 0.2), wide);
  return mix(c, vec3(0.1, 0.1, 0.3), thin * 0.7);
}
