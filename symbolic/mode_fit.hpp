// Rule 2, the mode fit (Li et al. 2020, Sec. 3.3): Y = f(X), X ~ N(mu, sigma^2), f monotone on a
// piece with inverse g. Y is fitted by the Gaussian whose peak is the peak of the density of Y:
// mY = the mode of f_Y(y) = phi((g(y) - mu)/sigma) |g'(y)| / sigma, sY = 1 / (sqrt(2 pi) f_Y(mY)).
// Li's mode equation g'(y)^2 (g(y) - mu) = sigma^2 g''(y) becomes, in x = g(y) (g' = 1/f',
// g'' = -f''/f'^3), q(x) = (x - mu) + sigma^2 f''(x)/f'(x) = 0; the mode is a root of q where q
// turns from negative to positive (a maximum of log f_Y). Then mY = f(x*) and
// sY = sigma |f'(x*)| exp((x* - mu)^2 / (2 sigma^2)).
#pragma once

#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <vector>

#include "catalog.hpp"
#include "derived.hpp"

namespace bl::sym {

const GiNaC::symbol& var_mu();
const GiNaC::symbol& var_sig();  // sigma of Rule 2 (printed "sigma")

struct ModePiece {
  Bound lo, hi;          // the monotone piece (for periodic atomics within one period)
  GiNaC::ex f, fp;       // f and f' on it
  GiNaC::ex q, dq;       // q(x) and q'(x), in x, mu, sigma
  int degree = -1;       // 1 or 2: the numerator of q is this polynomial in x (closed form); -1: Newton
  GiNaC::ex c2, c1, c0;  // that polynomial's coefficients
  int root = 0;          // degree 2: +1 takes (-c1 + sqrt(disc)) / (2 c2), -1 the other root
  GiNaC::ex y_equation;  // Li's eq. 13 from the catalog inverse: g'^2 (g - mu) - sigma^2 g''
};

struct ModeFit {
  const Atomic* atomic = nullptr;
  std::vector<ModePiece> pieces;  // in order along x
  std::optional<GiNaC::ex> period;
  std::string method;   // "closed form (...)" or "newton (...)"
  std::string formula;  // for the manifest
};

// Derives Rule 2 for every atomic where the fit is well posed; lists the others, with the reason,
// in *not_derived (kernel "gaussian", rule2).
std::vector<ModeFit> derive_mode_fits(const Catalog& cat, std::vector<NotDerived>* not_derived);

}  // namespace bl::sym
