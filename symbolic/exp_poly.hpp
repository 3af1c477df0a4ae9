// The exp-polynomial class on the whole line: finite sums c x^n e^{a x} with a real or imaginary
// (sin, cos, sinh, cosh, exp, powers and their products). Closed under products, so f^2 stays in
// it; every kernel maps a term to a closed form through its moment generating function.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>

#include "kernels.hpp"

namespace bl::sym {

struct ExpPolyKey {
  int n;              // power of x
  GiNaC::numeric a;   // exponent rate (complex rational; imaginary for sin/cos)
  bool operator<(const ExpPolyKey& o) const;
};

class ExpPoly {
 public:
  // Normal form of e (an expression in x); throws std::invalid_argument naming the offending
  // subexpression when e is outside the class.
  static ExpPoly from(const GiNaC::ex& e);
  ExpPoly operator*(const ExpPoly& o) const;
  ExpPoly operator+(const ExpPoly& o) const;
  // E[f(x + U)] as a real closed form in x and sigma.
  GiNaC::ex convolve(Kernel k) const;
  GiNaC::ex to_ex() const;
  // The terms c x^n e^{a x}, keyed by (n, a).
  const std::map<ExpPolyKey, GiNaC::numeric>& terms() const { return terms_; }

 private:
  std::map<ExpPolyKey, GiNaC::numeric> terms_;
  void add(const ExpPolyKey& k, const GiNaC::numeric& c);
};

}  // namespace bl::sym
