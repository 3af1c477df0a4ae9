// One-pass (mean, variance) entries: bl::gaussian::<f>_stat(x, sigma) = {E f(X), Var f(X)}, X ~
// N(x, sigma^2), for f = a + b x + c A(s x) with A a one-piece periodic atomic (fract, floor, ceil).
//
// A compiled program needs both moments of every smoothed node. The separate entries f~ and (f^2)~
// each pay for the reduction, one normal-table lookup per break and the Fourier chain (float:
// gaussian fract 11.2 ns, fract^2 beside it 13.3 more, nothing shared); the stat entry prints both
// from one pass of the straight-line plan (emit_gauss_periodic.hpp, two channels):
//   channel 0 = A~(y),  y = s x,
//   channel 1 = c^2 (A^2)~(y) + b^2 sigma^2 + 2 b c s sigma^2 (g1 + J theta(y)),
//   E f = a + b x + c channel0,   Var f = channel1 - c^2 channel0^2,
// from Var f = c^2 Var A(sX) + b^2 sigma^2 + 2 b c Cov(X, A(sX)) and Stein's identity
// Cov(X, A(sX)) = E[U A(y + sU)] = s sigma^2 E[A'(y + V)] = s sigma^2 (g1 + J theta(y)), where g(t) =
// g0 + g1 t is A's piece, J = g(0) - g(T) its jump and theta the periodised normal density (the
// identity fused_periodic in emit_common.cpp uses for floor^2).
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "emit_common.hpp"

namespace bl::rulegen {

struct StatPair {
  const Derived* f = nullptr;   // f's Gaussian entry
  const Derived* f2 = nullptr;  // f^2's (the generic fallback reads both)
  FusablePair A;                // A~ and (A^2)~
  GiNaC::numeric a = 0, b = 0, c = 1;
  int s = 1;
  std::string name() const;  // gaussian_fract_stat: C++ detail::gen::<name>, GLSL bl_<name>
};

// Every f of the catalog that fits, in the order of its entries.
std::vector<StatPair> stat_pairs(const std::vector<Derived>& ds);

// The definition of the entry: C++ `template <class T> stat<T> <name>(T x, T sigma)` or GLSL `vec2
// bl_<name>(float x, float sigma)` ((mean, var)).
std::string stat_pair_definition(const StatPair& p, Lang lang);

}  // namespace bl::rulegen
