#version 450
// Truchet tiles: each unit tile holds two quarter-circle arcs in one of two orientations, chosen by
// a hash of the tile (if/else), giving meandering curves.
float hash(vec2 p) { return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453); }

float arc(vec2 f, vec2 corner) {
  float d = abs(length(f - corner) - 0.5);  // distance to the arc of radius 1/2 around corner
  return 1.0 - smoothstep(0.06, 0.1, d);
}

vec3 shade(vec2 uv, float time) {
  vec2 p = uv * 2.0;
  vec2 tile = floor(p);
  vec2 f = fract(p);
  float line;
  if (hash(tile) < 0.5) {
    line = max(arc(f, vec2(0.0, 0.0)), arc(f, vec2(1.0, 1.0)));
  } else {
    line = max(arc(f, vec2(1.0, 0.0)), arc(f, vec2(0.0, 1.0)));
  }
  vec3 ground = mod(tile.x + tile.y, 2.0) < 1.0 ? vec3(0.92, 0.9, 0.82) : vec3(0.85, 0.88, 0.92);
  return mix(ground, vec3(0.1, 0.3, 0.5), line);
}
