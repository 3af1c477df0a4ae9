#version 450
// Greyscale checkerboard from floor (Dorn et al. Listing 1); the C++ twin is
// runtime/shaders/patterns.hpp checkerboard.
vec3 shade(vec2 uv, float time) {
  float ss = floor(uv.x + 0.5) - floor(uv.x);
  float tt = floor(uv.y + 0.5) - floor(uv.y);
  float c = ss * tt + (1.0 - ss) * (1.0 - tt);
  return vec3(0.1 + 0.8 * c);
}
