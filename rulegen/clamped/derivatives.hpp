// First and second derivatives of every catalog atomic, for Rule 3 (Taylor in the clamped domain)
// and for gradient propagation in the runtime compiler. Derived with GiNaC from the catalog
// definition; piecewise and periodic atomics differentiate their polynomial pieces (the delta
// functions at jumps are dropped: the derivative is the right piece's, 0 away from kinks).
#pragma once

#include <string>
#include <vector>

#include "derived.hpp"

namespace bl::rulegen::clamped {

struct DerivTerm {  // coeff * <atomic>_d<order>(arg_sign * x), for combinations
  GiNaC::numeric coeff;
  std::string atomic;
  int arg_sign;
};

struct Derivative {
  const sym::Atomic* atomic = nullptr;
  int order = 1;  // 1 or 2
  enum class Kind { Closed, Pieces, Periodic, Combination, Chain } kind{};
  GiNaC::ex closed;                    // Closed: f^(order)(x); Combination: the polynomial part's
  std::vector<sym::PolyPiece> pieces;  // Pieces / Periodic (one period)
  GiNaC::ex period;
  std::vector<DerivTerm> terms;  // Combination
  // Chain (exp-polynomial pieces): (hi, f^(order) on the piece), right-continuous at the breaks.
  std::vector<std::pair<sym::Bound, GiNaC::ex>> chain;
  std::string formula;           // manifest text

  std::string impl() const;  // deriv_sin_d1
  std::string cpp() const;   // bl::deriv::sin_d1
  std::string glsl() const;  // bl_deriv_sin_d1
};

// Both orders for every atomic of the catalog, in catalog order. `ds` supplies the combinations'
// linear identities (floor = x - fract(x)).
std::vector<Derivative> derive_derivatives(const sym::Catalog& cat, const std::vector<sym::Derived>& ds);

}  // namespace bl::rulegen::clamped
