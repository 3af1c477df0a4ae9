// Straight-line C++ for the Gaussian smoothing of a periodic piecewise polynomial (fract, square,
// triangle, their squares, and the fused fract terms of floor^2 / ceil^2 / trunc^2): a break regime
// for small sigma/T and an unrolled Fourier regime above it, both planned at emit time.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

namespace bl::rulegen {

struct GaussPeriodicSpec {
  GiNaC::numeric period;                  // T
  std::vector<GiNaC::numeric> lo;         // piece starts in [0, T), lo[0] = 0, increasing
  std::vector<std::vector<GiNaC::ex>> c;  // piece polynomials in t (coefficients may hold lam)
  GiNaC::ex a0, ak, bk;                   // Fourier coefficients in var_k, var_pk (and lam, sigma)
  double coef_bound = 0;                  // bound on |a_k| + |b_k| (lam counted as 1)
  GiNaC::ex delta;                        // weight / sigma of a Dirac delta at the break lo[0]
  GiNaC::ex break_extra;                  // added in the break regime only (Fourier: inside a0)
  std::string y = "x";                    // argument
  std::string lead;                       // "rest + " or ""
  // More outputs of the same pass (one piece only: fract and its combinations): each further
  // channel's c, a0, ak, bk, coef_bound, delta and break_extra (its period, lo, y and lead are
  // unused). The breaks, the normal table lookups and the Fourier chains are shared; `finish` is the
  // C++ expression returned instead of lead + acc, with @0 for the first channel's value and @1, @2
  // for the next ones'.
  std::vector<GaussPeriodicSpec> more;
  std::string finish;
};

// Statements that return the entry for float and double when the spec fits (dyadic period and
// breaks), guarded by `if constexpr`; other types fall through to the caller's generic code. ""
// when the spec does not fit.
std::string gauss_periodic_fast_cpp(const GaussPeriodicSpec& sp);
// The float regimes of the same plan as GLSL statements, guarded by sigma >= 1e-30 (the caller's
// generic code follows for smaller sigma); "" when the spec does not fit.
std::string gauss_periodic_fast_glsl(const GaussPeriodicSpec& sp);
// C++ only: the body of an entry that takes sigma below the nearest-break-alone bound by the break
// nearest to x (located by rint, no reduction by the period) and calls `general` (the full body,
// out of line) for the rest; "" where it does not apply (see emit_gauss_periodic.cpp).
// `clamp` and *in_range: see periodic_hot (emit_common.hpp).
std::string gauss_periodic_hot(const GaussPeriodicSpec& sp, const std::string& general,
                               const std::string& clamp, bool* in_range);

// The C++ text of a float regime (the straight-line break and Fourier forms here and in
// emit_box_tent_breaks.cpp) respelled as GLSL: a fixed map over a closed vocabulary; anything C++
// left over throws (std::logic_error) rather than reach a driver.
std::string glsl_spelling(std::string code);

}  // namespace bl::rulegen
