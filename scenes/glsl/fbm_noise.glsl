#version 450
// Four octaves of value noise (fbm), hash by fract(sin(dot())) as users write it.
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
float noise(vec2 p) {
  vec2 i = floor(p);
  vec2 f = fract(p);
  vec2 u = f * f * (3.0 - 2.0 * f);
  float a = hash(i), b = hash(i + vec2(1.0, 0.0)), c = hash(i + vec2(0.0, 1.0)), d = hash(i + vec2(1.0, 1.0));
  return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}
vec3 shade(vec2 uv, float time) {
  vec2 p = uv * 4.0;
  float v = 0.0, amp = 0.5;
  for (int k = 0; k < 4; k++) {
    v += amp * noise(p);
    p = p * 2.03 + vec2(1.7, 9.2);
    amp *= 0.5;
  }
  return mix(vec3(0.2, 0.1, 0.05), vec3(0.95, 0.8, 0.5), v);
}
