#version 450
// Rotated tiles, written the way shader authors write rotations (a mat2 times a vec2): a two-tone
// checkerboard turned by 30 degrees, each tile striped along its diagonal (the tile's own
// coordinates turned by another 45 degrees), with a thin dark grout line.
mat2 rotation(float a) {
  float c = cos(a), s = sin(a);
  return mat2(c, s, -s, c);  // columns: the images of the x and y axes
}

vec3 shade(vec2 uv, float time) {
  vec2 p = rotation(0.5236) * uv * 1.5;
  // square() is 1 on the first half of each unit period: the two halves of a 2-tile period.
  float sx = square(0.5 * p.x), sy = square(0.5 * p.y);
  float checker = sx + sy - 2.0 * sx * sy;
  vec2 q = rotation(-0.7854) * fract(p);
  float stripe = step(0.5, fract(q.x * 4.0));
  vec2 f = fract(p);
  float grout = step(0.04, f.x) * step(f.x, 0.96) * step(0.04, f.y) * step(f.y, 0.96);
  vec3 light = vec3(0.85, 0.78, 0.62), dark = vec3(0.22, 0.32, 0.45);
  vec3 tile = mix(light, dark, checker) * (0.8 + 0.2 * stripe);
  return mix(vec3(0.1), tile, grout);
}
