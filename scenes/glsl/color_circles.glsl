#version 450
// Aperiodic coloured circles: three layers with incommensurate periods; a later layer covers an
// earlier one.
const float scale[3] = float[](1.0, 1.618034, 2.414214);
const float offset[3] = float[](0.0, 0.31, 0.77);
const float radius2[3] = float[](0.12, 0.09, 0.06);
const vec3 colour[3] = vec3[](vec3(0.9, 0.3, 0.2), vec3(0.2, 0.7, 0.3), vec3(0.2, 0.4, 0.9));

vec3 shade(vec2 uv, float time) {
  vec3 c = vec3(0.85);
  for (int i = 0; i < 3; ++i) {
    float fu = fract(uv.x * scale[i] + offset[i]) - 0.5;
    float fv = fract(uv.y * scale[i] + offset[i] * 1.7) - 0.5;
    if (fu * fu + fv * fv < radius2[i]) c = colour[i];
  }
  return c;
}
