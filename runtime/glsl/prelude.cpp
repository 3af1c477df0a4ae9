#include "glsl/prelude.hpp"

namespace bl::glsl {

const std::vector<std::string>& prelude_atomics() {
  static const std::vector<std::string> names = {"saturate", "triangle", "square", "pow2", "pow3", "pow4",
                                                 "pow5",     "pow6",     "pow7",   "pow8", "inv",  "inv2"};
  return names;
}

const std::string& prelude() {
  static const std::string text = [] {
    // Scalar definitions: the catalog's plain functions (generated/bandlimit.glsl bl_plain_*).
    std::string s =
        "// bandlimit prelude: the catalog atomics GLSL lacks (paste before a shade() file)\n"
        "float saturate(float x) { return clamp(x, 0.0, 1.0); }\n"
        "float triangle(float x) { float t = mod(x, 2.0); return t < 1.0 ? t : 2.0 - t; }  // period 2\n"
        "float square(float x) { return fract(x) < 0.5 ? 1.0 : 0.0; }  // 1 on [0, 1/2), period 1\n"
        "float pow2(float x) { return x * x; }\n"
        "float pow3(float x) { return x * x * x; }\n"
        "float pow4(float x) { return pow2(x * x); }\n"
        "float pow5(float x) { return pow4(x) * x; }\n"
        "float pow6(float x) { return pow3(x * x); }\n"
        "float pow7(float x) { return pow6(x) * x; }\n"
        "float pow8(float x) { return pow4(x * x); }\n"
        "float inv(float x) { return 1.0 / x; }\n"
        "float inv2(float x) { return 1.0 / (x * x); }\n";
    // Component-wise vector overloads.
    for (const auto& f : prelude_atomics()) {
      s += "vec2 " + f + "(vec2 v) { return vec2(" + f + "(v.x), " + f + "(v.y)); }\n";
      s += "vec3 " + f + "(vec3 v) { return vec3(" + f + "(v.x), " + f + "(v.y), " + f + "(v.z)); }\n";
      s += "vec4 " + f + "(vec4 v) { return vec4(" + f + "(v.x), " + f + "(v.y), " + f + "(v.z), " + f +
           "(v.w)); }\n";
    }
    return s;
  }();
  return text;
}

}  // namespace bl::glsl
