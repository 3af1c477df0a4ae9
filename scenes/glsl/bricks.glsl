#version 450
// Bricks with mortar in running bond and a smooth per-brick brightness hash.
const float mortar = 0.06;

vec3 shade(vec2 uv, float time) {
  float y = uv.y * 2.0;
  float row = floor(y);
  // Every other row shifted by half a brick: square(y / 2) is 1 on even rows.
  float x = uv.x + 0.5 * square(y * 0.5);
  float col = floor(x);
  float fx = fract(x), fy = fract(y);
  float brick = step(mortar, fx) * step(fx, 1.0 - mortar) * step(mortar, fy) * step(fy, 1.0 - mortar);
  float noise = 0.5 + 0.5 * sin(row * 1.7 + col * 2.9);
  vec3 brick_colour = vec3(0.6, 0.22, 0.12) * (0.75 + 0.35 * noise);
  return mix(vec3(0.75), brick_colour, brick);
}
