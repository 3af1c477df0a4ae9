// See taylor.hpp.
#include "taylor.hpp"

#include <boost/math/differentiation/autodiff.hpp>
#include <complex>

namespace nb::taylor {

std::vector<double> derivatives(double x) {
  using boost::math::differentiation::make_fvar;
  const auto u = make_fvar<double, kOrder>(x);
  const auto f = sin(u * u) + u * u / 100.0;
  std::vector<double> d(kOrder + 1);
  for (int n = 0; n <= kOrder; ++n) d[n] = f.derivative(n);
  return d;
}

std::vector<double> exact_derivatives(double x) {
  using C = std::complex<double>;
  const C e = std::exp(C(0, x * x));
  std::vector<C> p = {C(1)};  // coefficients of P_n, lowest degree first
  std::vector<double> d(kOrder + 1);
  for (int n = 0; n <= kOrder; ++n) {
    C v = 0;
    for (size_t j = p.size(); j-- > 0;) v = v * x + p[j];
    d[n] = std::imag(e * v) + (n == 0 ? x * x / 100 : n == 1 ? x / 50 : n == 2 ? 0.02 : 0.0);
    std::vector<C> q(p.size() + 1, C(0));  // P' + 2ix P
    for (size_t j = 1; j < p.size(); ++j) q[j - 1] += C(double(j)) * p[j];
    for (size_t j = 0; j < p.size(); ++j) q[j + 1] += C(0, 2) * p[j];
    p = q;
  }
  return d;
}

double truncated(const std::vector<double>& d, double s, int terms) {
  double acc = 0, c = 1;  // c = s^(2k) / (2^k k!)
  for (int k = 0; k < terms && 2 * k < static_cast<int>(d.size()); ++k) {
    acc += c * d[2 * k];
    c *= s * s / (2.0 * (k + 1));
  }
  return acc;
}

double gain(double s, double w, int terms) {
  const double a = -s * s * w * w / 2;
  double acc = 0, t = 1;
  for (int k = 0; k < terms; ++k) {
    acc += t;
    t *= a / (k + 1);
  }
  return acc;
}

}  // namespace nb::taylor
