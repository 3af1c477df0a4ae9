#version 450
// Woven plaid: thread bands in u and v, the over/under weave by a checker of the thread cells.
vec3 shade(vec2 uv, float time) {
  vec2 p = uv * 6.0;
  float wu = step(0.5, fract(p.x * 0.5)), wv = step(0.5, fract(p.y * 0.5));
  float band_u = smoothstep(0.2, 0.3, abs(fract(p.x) - 0.5));
  float band_v = smoothstep(0.2, 0.3, abs(fract(p.y) - 0.5));
  float over = mod(floor(p.x * 4.0) + floor(p.y * 4.0), 2.0);
  vec3 cu = mix(vec3(0.7, 0.1, 0.1), vec3(0.1, 0.2, 0.6), wu);
  vec3 cv = mix(vec3(0.1, 0.5, 0.2), vec3(0.9, 0.8, 0.3), wv);
  vec3 thread = mix(cu, cv, over);
  return mix(thread, vec3(0.05), band_u * band_v);
}
