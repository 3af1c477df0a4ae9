#version 450
// Faux fire: turbulence (sum of |sin| octaves, each warped by the previous) rising with time,
// through a black-red-yellow-white ramp.
vec3 shade(vec2 uv, float time) {
  float n = 0.0;
  float x = uv.x, y = uv.y - time * 0.8;
  float amp = 0.5, freq = 1.0;
  for (int o = 0; o < 5; ++o) {
    float warp = sin(y * (freq * 1.3) + n * 2.0 + float(o));
    n += amp * abs(sin(x * freq + warp + time * (0.5 * float(o + 1))));
    amp *= 0.5;
    freq *= 2.03;
  }
  float heat = clamp(n * 1.4 - 0.2 + 0.15 * sin(uv.y * 0.7), 0.0, 1.0);
  return vec3(smoothstep(0.0, 0.5, heat), smoothstep(0.3, 0.8, heat), smoothstep(0.7, 1.0, heat));
}
