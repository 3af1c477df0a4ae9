// Helpers of the generated GLSL besides the support functions.
float bl_nan() { return uintBitsToFloat(0x7fc00000u); }
float bl_pi() { return 3.14159265358979; }
float bl_pow4(float v) { float v2 = v * v; return v2 * v2; }  // see emit_helpers.hpp
float bl_series_reach() { return 0.35; }  // see emit_helpers.hpp
// Clausen's Cl2 and the dilogarithm on [-1, 0]: see emit_helpers.hpp.
float bl_clausen2(float t) {
  const float c[13] = float[13](0.013888888888888888, 6.9444444444444444e-05, 7.873519778281683e-07,
                              1.1482216343327455e-08, 1.8978869988970999e-10, 3.3873013709535212e-12,
                              6.3726364431831808e-14, 1.2462059912950672e-15, 2.5105444608999545e-17,
                              5.1782588060906232e-19, 1.0887357368300849e-20, 2.3257441143020871e-22,
                              5.0351952131473897e-24);
  float two_pi = 2.0 * bl_pi();
  float r = t - two_pi * floor((t + bl_pi()) / two_pi);
  if (r == 0.0) return 0.0;
  float r2 = r * r;
  float p = r * r2;
  float sum = 0.0;
  for (int k = 0; k < 13; ++k) {
    sum += c[k] * p;
    p *= r2;
  }
  return r - r * log(abs(r)) + sum;
}
float bl_li2_series(float y) {
  float sum = 0.0;
  float p = y;
  for (int k = 1; k <= 30; ++k) {
    sum += p / float(k * k);
    p *= y;
    // |y| <= 1/2: the tail is at most 2 |y|^(k+1)/(k+1)^2 (see emit_helpers.hpp)
    if (2.0 * abs(p) <= 3e-8 * abs(sum) * float((k + 1) * (k + 1))) break;
  }
  return sum;
}
float bl_li2_landen(float z) {  // z in [-1, 0]
  if (z >= -0.5) return bl_li2_series(z);
  float l = log(1.0 - z);
  return -bl_li2_series(z / (z - 1.0)) - l * l / 2.0;
}
float bl_li2(float z) {  // z <= 0 (GLSL has no recursion: inversion then Landen)
  if (z < -1.0) {
    float l = log(-z);
    return -bl_pi() * bl_pi() / 6.0 - l * l / 2.0 - bl_li2_landen(1.0 / z);
  }
  return bl_li2_landen(z);
}
float bl_prod0(float a, float b) { return a == 0.0 ? 0.0 : a * b; }
float bl_sgn(float x) { return sign(x); }
