// Independent checks of the notebook's quadrature reference: closed forms of E[f(X)],
// X ~ N(mu, s^2), for the Table 1 functions, and adaptive Gauss-Kronrod for Figure 4's function.
#pragma once

#include <functional>

namespace nb::clamped {

// E[exp(g X^2)] = exp(g mu^2 / (1 - 2 g s^2)) / sqrt(1 - 2 g s^2) (g < 1 / (2 s^2)).
double gauss_exp_gx2(double g, double mu, double s);

// E[f(X)] by adaptive 61-point Gauss-Kronrod over mu +- 12 s (Boost.Math), tolerance 1e-14.
double gauss_kronrod(const std::function<double(double)>& f, double mu, double s);

}  // namespace nb::clamped
