// Bivariate Gaussian rules (Yang & Barnes 2018, Sec. 4.4): for A, B jointly normal (means ma, mb,
// standard deviations sa, sb, correlation rho) the mean and variance of A op B, derived from
// normal moments by gauss_expect.hpp, never typed in. Each rule is a list of locals, a mean and a
// variance in the argument symbols; where the emitted arrangement differs from the derived one (to
// avoid cancellation), the engine proves the two equal before using it.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

namespace bl::sym {

// The argument and local symbols the rules are written in (printed by name).
struct BivariateSymbols {
  GiNaC::symbol ma{"ma"}, sa{"sa"}, mb{"mb"}, sb{"sb"}, rho{"rho"};  // A, B and their correlation
  GiNaC::symbol mc{"mc"}, sc{"sc"};                                  // select's condition
  GiNaC::symbol s2{"s2"}, s{"s"}, t{"t"}, cv{"cv"};                  // locals of min/max/compare
  GiNaC::symbol sn{"sn"}, mu{"mu"};                                  // locals of mod
};
const BivariateSymbols& biv();

struct BivariateRule {
  std::string op;                                           // add sub mul min max less greater select mod
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> locals;  // in order; later ones may use earlier ones
  GiNaC::ex mean, var;
  std::string formula;     // text for the manifest
  std::string assumption;  // what the rule assumes beyond joint normality
  std::string method;      // "closed form (...)"
};

// The derived rules, in a fixed order. Throws std::runtime_error if an emitted stable form does
// not equal its derivation.
std::vector<BivariateRule> derive_bivariate();

// The product variance as printed in Yang & Barnes 2018 eq. 4.9 (ma^2 sb + sa mb^2 + ...): kept
// only so that tests can show it differs from the derivation.
GiNaC::ex paper_product_variance_eq49();

}  // namespace bl::sym
