// Types of the generated entry registry (generated/bandlimit/registry.hpp). Copied verbatim by
// `rulegen emit`. The registry lists every emitted function with the facts a verifier or a
// benchmark needs, as templates over the scalar type so one table serves float, double and
// multiprecision (everything emitted is written with unqualified math calls and `using std::`).
#pragma once

#include "emit_helpers.hpp"  // bl::stat

namespace bl {
namespace registry {

// What the catalog says about one atomic function, as the verifier needs it.
struct AtomicInfo {
  const char* name;
  const char* cls;        // "entire" | "piecewise" | "periodic" | "quasiperiodic" | "antiderivative"
  double period;          // 0 when not periodic
  int nbreaks;            // jumps, kinks and singularities; for periodic atomics those in [0, period)
  double breaks[8];       //   (repeat every period)
  int nsingular;          // singularities (poles, domain ends): the compact kernel keeps away from them
  double singular[4];     //   (repeat every period when period > 0)
  double domain_lo;       // -inf / +inf allowed; the function is defined on (domain_lo, domain_hi)
  double domain_hi;
  double range_lo;        // closed bounds of f (may be infinite)
  double range_hi;
  bool indicator;         // f takes only the values 0 and 1 (step, square, pulse30): f^2 = f everywhere
};

template <class T>
struct Entry {
  const AtomicInfo* atomic;
  const char* kernel;     // "gaussian" | "box" | "tent"
  bool squared;           // true: the entry is the convolution of f^2
  const char* rule;       // "convolution" | "moment" | ... (rules beyond plain convolution)
  int order;              // moment order n for rule "moment", else 0
  bool compact;           // box/tent half-width limited to lambda * (distance to nearest singularity)
  double lambda;          // that lambda (1/2), 0 when not compact
  const char* cpp;        // qualified C++ name
  const char* glsl;       // GLSL name
  T (*smoothed)(T x, T sigma);
  T (*plain)(T x);        // f itself (not squared): the integrand is plain or plain^2
};

// A univariate rule beyond plain convolution (issue 3: "rule1", "rule2", "rule3", "bimodal", ...):
// maps the input's (mean, standard deviation) to the output's stat (mean, variance).
template <class T>
struct RuleEntry {
  const AtomicInfo* atomic;
  const char* rule;       // "rule1" | "rule2" | "rule3" | "bimodal" | ...
  const char* kernel;     // "gaussian" | "box" | "tent"
  const char* method;     // how it is computed, e.g. "closed form", "newton(6)"
  const char* cpp;        // qualified C++ name, callable as cpp(mu, sigma) -> bl::stat<T>
  const char* glsl;       // GLSL name, vec2 (mean, var) glsl(float mu, float sigma)
  stat<T> (*fn)(T mu, T sigma);
};

// A bivariate Gaussian operator ("add", "sub", "mul", "div", "min", "max", "less", ...): inputs
// A, B jointly normal with means ma, mb, standard deviations sa, sb and correlation rho.
template <class T>
struct BinaryEntry {
  const char* op;
  const char* cpp;        // callable as cpp(ma, sa, mb, sb, rho) -> bl::stat<T>
  const char* glsl;       // vec2 glsl(float ma, float sa, float mb, float sb, float rho)
  stat<T> (*fn)(T ma, T sa, T mb, T sb, T rho);
};

}  // namespace registry
}  // namespace bl
