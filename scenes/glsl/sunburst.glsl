#version 450
// A sunburst: rays by polar angle (atan(y, x), as shader authors write it), rings by radius, the
// rays twisting with the radius. The angle jumps by 2 pi on the negative x axis, where 12 whole
// rays keep the pattern continuous.
vec3 shade(vec2 uv, float time) {
  vec2 p = uv - vec2(1.0, 0.5);
  float r = length(p);
  float a = atan(p.y, p.x);                        // -pi .. pi
  float rays = step(0.5, fract(a * 12.0 / 6.2831853 + 0.8 * r));
  float rings = smoothstep(0.35, 0.65, fract(r * 2.0));
  vec3 warm = vec3(0.95, 0.75, 0.3), deep = vec3(0.55, 0.15, 0.1);
  return mix(deep, warm, rays) * (0.7 + 0.3 * rings);
}
