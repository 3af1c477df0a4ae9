#version 450
// Hexagonal tiles with dark grout, Shadertoy style: the nearer of two offset rectangular lattices.
float hexDist(vec2 p) {
  p = abs(p);
  return max(dot(p, normalize(vec2(1.0, 1.73))), p.x);
}
vec3 shade(vec2 uv, float time) {
  vec2 s = vec2(1.0, 1.7320508);
  vec2 p = uv * 3.0;
  vec2 a = mod(p, s) - 0.5 * s;
  vec2 b = mod(p - 0.5 * s, s) - 0.5 * s;
  vec2 g = dot(a, a) < dot(b, b) ? a : b;
  float d = hexDist(g);
  float edge = smoothstep(0.42, 0.46, d);
  return mix(vec3(0.9, 0.85, 0.7), vec3(0.15, 0.1, 0.1), edge);
}
