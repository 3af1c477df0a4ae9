#version 450
// The suite's textured_tiles in GLSL: the "albedo" texture slot (the scene binds a file to it) with
// dark grout lines every half unit on top.
uniform sampler2D albedo;

vec3 shade(vec2 uv, float time) {
  vec3 colour = texture(albedo, uv).rgb;
  float gu = fract(uv.x * 2.0), gv = fract(uv.y * 2.0);
  bool grout = gu < 0.06 || gv < 0.06;
  return grout ? vec3(0.06) : colour;
}
