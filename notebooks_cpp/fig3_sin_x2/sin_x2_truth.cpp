// See sin_x2_truth.hpp.
#include "sin_x2_truth.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

namespace nb::sin_x2 {

double gauss_sin_x2(double x, double s) {
  const double q = 1 + 4 * s * s * s * s;  // |1 - 2i s^2|^2
  return std::pow(q, -0.25) * std::exp(-2 * s * s * x * x / q) *
         std::sin(x * x / q + 0.5 * std::atan(2 * s * s));
}

double gauss_x2(double x, double s) {
  return x * x + s * s;
}

double quad_sin_x2(double x, double s) {
  const double inv_sqrt_2pi = boost::math::constants::one_div_root_two_pi<double>();
  auto f = [&](double z) {
    const double t = x + s * z;
    return inv_sqrt_2pi * std::exp(-0.5 * z * z) * std::sin(t * t);
  };
  // The integrand oscillates (up to ~2|x + sz| s per unit z): adaptive, deep, tight tolerance.
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, -12.0, 12.0, 20, 1e-14);
}

}  // namespace nb::sin_x2
