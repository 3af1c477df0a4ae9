// Back ends: print a lowered Program as a self-contained C++ function or GLSL function.
#pragma once

#include <string>

#include "compiler/lir.hpp"

namespace bl::compiler {

// C++: a header defining
//   inline void <name>(const float* bl_m, const float* bl_s, const float* bl_gx, const float* bl_gy,
//                      float* bl_out)
// in namespace bl_shaders (bl_m/bl_s: per-input mean and sd; bl_gx/bl_gy: per-input screen
// gradient, unused unless the program needs gradients; bl_out: the outputs). It includes only the
// generated headers whose functions it calls. `comment` goes in the banner.
// Header: it starts with #pragma once (a file to include); Source: without it (the start of a
// translation unit, as bl::jit compiles it with its pixel loop).
enum class CppForm { Header, Source };
std::string emit_cpp(const Program& p, const std::string& name, const std::string& comment = "",
                     CppForm form = CppForm::Header);

// A footprint-LOD pair (tuner/lod.hpp) as one C++ header: emit_cpp of each as <name>_near and
// <name>_far, and <name> with the same signature, which runs the near one where the pixel's footprint,
// max(bl_s[u], bl_s[v]) over the inputs named u and v, is below `limit` and the far one elsewhere.
// Throws std::invalid_argument when the programs differ in inputs, outputs or textures, an input u or
// v is missing, or the limit is not a finite number >= 0.
std::string emit_cpp_lod(const Program& near, const Program& far, float limit, const std::string& name,
                         const std::string& comment = "", CppForm form = CppForm::Header);

// GLSL: the generated library functions the program calls (and what they call, nothing else),
// then
//   void <name>(in float bl_m[NI], in float bl_s[NI], in float bl_gx[NI], in float bl_gy[NI],
//               out float bl_out[NO])
// No #version line: the includer supplies it (valid as 450 and 320 es).
std::string emit_glsl(const Program& p, const std::string& name, const std::string& comment = "");
// The footprint-LOD pair in GLSL: one library slice for both, <name>_near and <name>_far, and <name>
// (emit_glsl's signature) choosing between them as emit_cpp_lod does; the same errors.
std::string emit_glsl_lod(const Program& near, const Program& far, float limit, const std::string& name,
                          const std::string& comment = "");

std::string float_literal_cpp(float v);
std::string float_literal_glsl(float v);

}  // namespace bl::compiler
