// blverify: the generated registry (generated/bandlimit/registry.hpp) seen through plain data, so
// that only registry_view.cpp (double, float) and reference_mp.cpp (50 digits) include it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "spec.hpp"

namespace blv {

struct EntryView {
  int index = 0;  // position in bl::registry::entries<T>()
  std::string cpp, glsl, kernel, rule, atomic, cls;
  bool squared = false, compact = false;
  int order = 0;
  double lambda = 0;
  Spec spec;  // what the reference needs (integrand f^power, breaks, ...)
  double (*smoothed_d)(double, double) = nullptr;
  float (*smoothed_f)(float, float) = nullptr;
  float (*plain_f)(float) = nullptr;
  bool kernel_known = true;  // kernel is gaussian|box|tent
  bool exact_rule = true;    // rule "convolution" or "moment": bounds apply
};

// A one-pass stat entry ({E f, Var f}, bl::registry::stat_entries): its name, the registry names of
// the f and f^2 entries whose references check it, and its float and double evaluations.
struct StatView {
  std::string cpp, f_cpp, f2_cpp;
  std::function<void(double x, double sigma, double* mean, double* var)> eval_d;
  std::function<void(float x, float sigma, float* mean, float* var)> eval_f;
};

// False when blverify was built without generated/bandlimit/registry.hpp.
bool registry_compiled_in();
// All entries; *error names any inconsistency between the float and double instantiations.
std::vector<EntryView> load_registry(std::string* error);
// The stat entries (empty for a tree without them).
std::vector<StatView> load_stats(std::string* error);

}  // namespace blv
