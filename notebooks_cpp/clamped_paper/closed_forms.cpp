// See closed_forms.hpp.
#include "closed_forms.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

namespace nb::clamped {

double gauss_exp_gx2(double g, double mu, double s) {
  const double q = 1 - 2 * g * s * s;
  return std::exp(g * mu * mu / q) / std::sqrt(q);
}

double gauss_kronrod(const std::function<double(double)>& f, double mu, double s) {
  const double c = boost::math::constants::one_div_root_two_pi<double>();
  auto w = [&](double z) { return c * std::exp(-0.5 * z * z) * f(mu + s * z); };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(w, -12.0, 12.0, 20, 1e-14);
}

}  // namespace nb::clamped
