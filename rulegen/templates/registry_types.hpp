// Types of the generated entry registry (generated/bandlimit/registry.hpp). Copied verbatim by
// `rulegen emit`. The registry lists every emitted function with the facts a verifier or a
// benchmark needs, as templates over the scalar type so one table serves float, double and
// multiprecision (everything emitted is written with unqualified math calls and `using std::`).
#pragma once

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

}  // namespace registry
}  // namespace bl
