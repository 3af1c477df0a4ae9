#version 450
// Cellular (Voronoi / Worley) pattern: distance to the nearest of one jittered feature point per
// cell, searched over the 3x3 neighbourhood, with dark cell borders and a per-cell colour.
vec2 hash2(vec2 p) {
  return fract(sin(vec2(dot(p, vec2(127.1, 311.7)), dot(p, vec2(269.5, 183.3)))) * 43758.5453);
}

vec3 shade(vec2 uv, float time) {
  vec2 p = uv * 1.5;
  vec2 cell = floor(p);
  vec2 f = fract(p);
  float best = 8.0, second = 8.0;
  vec2 best_id = vec2(0.0);
  for (int j = -1; j <= 1; j++) {
    for (int i = -1; i <= 1; i++) {
      vec2 g = vec2(float(i), float(j));
      vec2 o = 0.15 + 0.7 * hash2(cell + g);  // feature point inside the neighbour cell
      vec2 r = g + o - f;
      float d = dot(r, r);
      if (d < best) {
        second = best;
        best = d;
        best_id = cell + g;
      } else if (d < second) {
        second = d;
      }
    }
  }
  float edge = smoothstep(0.0, 0.12, sqrt(second) - sqrt(best));  // 0 on the border between cells
  vec3 colour = 0.5 + 0.4 * cos(6.2831 * (hash2(best_id).x + vec3(0.0, 0.33, 0.67)));
  return colour * (0.35 + 0.65 * edge);
}
