// Ground truth for the sin(x^2) figures: the exact Gaussian smoothing E[sin((x + sZ)^2)], Z ~ N(0, 1),
// in closed form, and an independent Boost.Math quadrature of the same expectation to check it.
#pragma once

namespace nb::sin_x2 {

// E[sin((x + sZ)^2)] = (1 + 4s^4)^(-1/4) exp(-2 s^2 x^2 / (1 + 4s^4)) sin(x^2 / (1 + 4s^4) + atan(2s^2)/2):
// the imaginary part of E[exp(i (x + sZ)^2)] = (1 - 2i s^2)^(-1/2) exp(i x^2 / (1 - 2i s^2)).
double gauss_sin_x2(double x, double s);

// E[(x + sZ)^2] = x^2 + s^2.
double gauss_x2(double x, double s);

// The same expectation as gauss_sin_x2 by adaptive Gauss-Kronrod quadrature over z in [-12, 12]
// (the Gaussian beyond carries < 1e-32).
double quad_sin_x2(double x, double s);

}  // namespace nb::sin_x2
