#version 450
// Value noise (three octaves of fBm) from the classic sine hash, mapped through a two-colour ramp:
// the way shader authors write "noise" without a texture.
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }

float noise(vec2 p) {
  vec2 i = floor(p);
  vec2 f = fract(p);
  vec2 w = f * f * (3.0 - 2.0 * f);  // smooth interpolation weights
  float a = hash(i);
  float b = hash(i + vec2(1.0, 0.0));
  float c = hash(i + vec2(0.0, 1.0));
  float d = hash(i + vec2(1.0, 1.0));
  return mix(mix(a, b, w.x), mix(c, d, w.x), w.y);
}

vec3 shade(vec2 uv, float time) {
  vec2 p = uv * 2.0;
  float n = 0.0, amp = 0.5;
  for (int o = 0; o < 3; o++) {
    n += amp * noise(p);
    p = p * 2.0 + vec2(3.1, 1.7);
    amp *= 0.5;
  }
  n = n / 0.875;
  return mix(vec3(0.1, 0.15, 0.35), vec3(0.95, 0.85, 0.6), smoothstep(0.3, 0.7, n));
}
