// The generated functions the compiler may call, gathered from the generated registries (the
// table's convolutions, plain functions, and the rule headers): names for the C++ and GLSL back ends
// and float pointers for the evaluator.
#pragma once

#include <bandlimit/emit_helpers.hpp>
#include <string>
#include <vector>

namespace bl::compiler {

struct Function {
  std::string cpp;    // qualified C++ name
  std::string glsl;   // GLSL name
  int arity = 1;      // 1..6 float arguments
  bool stat = false;  // returns bl::stat<float> / vec2 (mean, var)
  // A one-pass stat entry (bl::gaussian::fract_stat): the index of its mean's own entry
  // (bl::gaussian::fract), which a program calls instead when it reads no variance; else -1.
  int mean_entry = -1;
  // Exactly one pointer is set, by arity and stat.
  float (*f1)(float) = nullptr;
  float (*f2)(float, float) = nullptr;
  bl::stat<float> (*s2)(float, float) = nullptr;
  bl::stat<float> (*s3)(float, float, float) = nullptr;
  bl::stat<float> (*s5)(float, float, float, float, float) = nullptr;
  bl::stat<float> (*s6)(float, float, float, float, float, float) = nullptr;
};

const std::vector<Function>& functions();
int find_function(const std::string& cpp_name);  // -1 when the table has no such function

// Names by convention (the generated table's): plain f, kernel f and f^2, rules.
std::string plain_name(const std::string& atomic);  // bl::plain::sin
std::string kernel_name(const std::string& kernel, const std::string& atomic,
                        bool squared);  // bl::gaussian::sin_sq
// {E f, Var f} from one pass (rulegen/emit_stat_pairs.hpp): bl::gaussian::fract_stat.
std::string stat_name(const std::string& kernel, const std::string& atomic);

}  // namespace bl::compiler
