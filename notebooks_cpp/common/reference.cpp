// See reference.hpp. Everything here is written from the definitions (DESIGN.md conventions), not
// from the generated code: kernel(x, s) = E[f(x + U)].
#include "reference.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace nb::ref {
namespace {

using R50 = boost::multiprecision::cpp_bin_float_50;
using R100 = boost::multiprecision::cpp_bin_float_100;

template <class R>
Exact to_exact(const R& v) {
  const double hi = static_cast<double>(v);
  if (!std::isfinite(hi)) return {hi, 0.0};
  return {hi, static_cast<double>(R(v - R(hi)))};
}

template <class R>
R pi() {
  return boost::math::constants::pi<R>();
}
template <class R>
R phi(const R& z) {
  return exp(-z * z / 2) / sqrt(2 * pi<R>());
}
template <class R>
R Phi(const R& z) {
  return boost::math::erfc(-z / sqrt(R(2))) / 2;
}

// E[fract(x + sZ)^p], p = 1 or 2, at 50 digits.
R50 gauss_fract_p(double xd, double sd, int p) {
  const R50 x = xd, s = sd, xr = x - floor(x);
  if (sd == 0) return p == 1 ? xr : xr * xr;
  if (sd >= 0.25) {
    // Fourier series of fract^p damped by the Gaussian's characteristic function e^{-2 pi^2 k^2 s^2}.
    R50 acc = p == 1 ? R50(1) / 2 : R50(1) / 3;
    for (int k = 1;; ++k) {
      const R50 damp = exp(-2 * pi<R50>() * pi<R50>() * k * k * s * s);
      if (damp < R50(1e-60)) break;
      const R50 th = 2 * pi<R50>() * k * xr;
      acc -= damp * sin(th) / (pi<R50>() * k);
      if (p == 2) acc += damp * cos(th) / (pi<R50>() * pi<R50>() * k * k);
    }
    return acc;
  }
  // Image sum: period m contributes int_m^{m+1} (t-m)^p N(t; x_r, s) dt; with z = (t - x_r)/s and
  // d = x_r - m that is sum_j C(p,j) d^{p-j} s^j I_j, I_j = int_a^b z^j phi. Beyond |z| = 16 the
  // Gaussian carries < 1e-56.
  const R50 z = 16;
  R50 acc = 0;
  const long m0 = static_cast<long>(floor(xr - z * s)), m1 = static_cast<long>(floor(xr + z * s));
  for (long m = m0; m <= m1; ++m) {
    const R50 a = (m - xr) / s, b = (m + 1 - xr) / s, d = xr - m;
    const R50 I0 = Phi(b) - Phi(a), I1 = phi(a) - phi(b), I2 = I0 + a * phi(a) - b * phi(b);
    acc += p == 1 ? d * I0 + s * I1 : d * d * I0 + 2 * d * s * I1 + s * s * I2;
  }
  return acc;
}

// int_0^y fract and its integral, exact (q = floor(y), r = fract(y)).
R100 F1_fract(const R100& y) {
  const R100 q = floor(y), r = y - q;
  return q / 2 + r * r / 2;
}
R100 F2_fract(const R100& y) {
  const R100 q = floor(y), r = y - q;
  return q * (q - 1) / 4 + q / 6 + q * r / 2 + r * r * r / 6;
}

// Compact half-width: min(h, r/2) with r the exact distance to the nearest singularity.
R100 compact_half_width(const std::string& f, const R100& x, const R100& h) {
  R100 r;
  if (f.rfind("tan", 0) == 0) {
    const R100 xr = x - pi<R100>() * floor(x / pi<R100>());
    r = abs(xr - pi<R100>() / 2);
  } else {
    r = x;
  }
  return h < r / 2 ? h : r / 2;
}

R100 F_compact(const std::string& f, const R100& y) {
  if (f == "tan") return -log(abs(cos(y)));
  if (f == "tan_sq") return tan(y) - y;
  if (f == "log") return y * log(y) - y;
  if (f == "log_sq") {
    const R100 l = log(y);
    return y * (l * l - 2 * l + 2);
  }
  throw std::invalid_argument("no antiderivative for " + f);
}

R50 f_compact(const std::string& f, const R50& t) {
  if (f == "tan") return tan(t);
  if (f == "tan_sq") return tan(t) * tan(t);
  if (f == "log") return log(t);
  if (f == "log_sq") return log(t) * log(t);
  throw std::invalid_argument("no function " + f);
}

// tanh_sinh in 50 digits over [a, b] (a < b).
template <class F>
R50 quad(F f, const R50& a, const R50& b) {
  static boost::math::quadrature::tanh_sinh<R50> integrator;  // not const-callable in Boost 1.74
  if (!(a < b)) return R50(0);
  return integrator.integrate(f, a, b, R50(1e-40));
}

// int over [lo, hi] of w(t) fract(t), split at the integers inside.
template <class W>
R50 quad_fract(W w, const R50& lo, const R50& hi) {
  R50 acc = 0;
  for (R50 m = floor(lo); m < hi; m += 1) {
    const R50 a = m > lo ? m : lo, b = m + 1 < hi ? m + 1 : hi;
    acc += quad([&](const R50& t) { return w(t) * (t - m); }, a, b);
  }
  return acc;
}

}  // namespace

double rel_error(double v, Exact r) {
  if (!std::isfinite(v)) return std::isfinite(r.hi) ? std::numeric_limits<double>::infinity() : 0.0;
  const double d = std::fabs((v - r.hi) - r.lo);
  return d / std::fmax(1.0, std::fabs(r.hi));
}

Exact gauss_fract(double x, double s) {
  return to_exact(gauss_fract_p(x, s, 1));
}
Exact gauss_fract_sq(double x, double s) {
  return to_exact(gauss_fract_p(x, s, 2));
}
Exact gauss_floor(double x, double s) {
  return to_exact(R50(x) - gauss_fract_p(x, s, 1));
}

Exact gauss_pow(double xd, double sd, int n) {
  const R100 x = xd, s = sd;
  R100 acc = 0, binom = 1, dfact = 1;
  for (int j = 0; 2 * j <= n; ++j) {
    acc += binom * pow(x, n - 2 * j) * pow(s, 2 * j) * dfact;
    binom = binom * (n - 2 * j) * (n - 2 * j - 1) / ((2 * j + 1) * (2 * j + 2));
    dfact *= 2 * j + 1;
  }
  return to_exact(acc);
}

Exact box_fract(double xd, double sd) {
  const R100 x = xd, h = sqrt(R100(3)) * R100(sd);
  return to_exact((F1_fract(x + h) - F1_fract(x - h)) / (2 * h));
}

Exact tent_fract(double xd, double sd) {
  const R100 x = xd, w = sqrt(R100(6)) * R100(sd);
  return to_exact((F2_fract(x + w) - 2 * F2_fract(x) + F2_fract(x - w)) / (w * w));
}

Exact box_pow(double xd, double sd, int n) {
  const R100 x = xd, h = sqrt(R100(3)) * R100(sd);
  return to_exact((pow(x + h, n + 1) - pow(x - h, n + 1)) / (2 * (n + 1) * h));
}

Exact box_compact(const std::string& f, double xd, double sd) {
  const R100 x = xd, hh = compact_half_width(f, x, sqrt(R100(3)) * R100(sd));
  return to_exact((F_compact(f, x + hh) - F_compact(f, x - hh)) / (2 * hh));
}

Exact tent_compact(const std::string& f, double xd, double sd) {
  if (f != "log") throw std::invalid_argument("tent_compact: only log");
  const R100 x = xd, w = compact_half_width(f, x, sqrt(R100(6)) * R100(sd));
  auto F2 = [](const R100& y) { return y * y / 2 * log(y) - R100(3) / 4 * y * y; };
  return to_exact((F2(x + w) - 2 * F2(x) + F2(x - w)) / (w * w));
}

double check_gauss_fract(double xd, double sd) {
  // E[fract(x + sZ)] = int phi(z) fract(x + s z) dz over |z| <= 16, split where x + s z is an integer.
  const R50 x = xd, s = sd;
  const R50 q = quad_fract([&](const R50& t) { return phi((t - x) / s) / s; }, x - 16 * s, x + 16 * s);
  return std::fabs(static_cast<double>(q - gauss_fract_p(xd, sd, 1)));
}

double check_box_fract(double xd, double sd) {
  const R50 x = xd, h = sqrt(R50(3)) * R50(sd);
  const R50 q = quad_fract([&](const R50&) { return 1 / (2 * h); }, x - h, x + h);
  const Exact e = box_fract(xd, sd);
  return std::fabs(static_cast<double>(q - R50(e.hi) - R50(e.lo)));
}

double check_tent_fract(double xd, double sd) {
  const R50 x = xd, w = sqrt(R50(6)) * R50(sd);
  auto tent = [&](const R50& t) { return (w - abs(t - x)) / (w * w); };
  const R50 q = quad_fract(tent, x - w, x) + quad_fract(tent, x, x + w);  // split at the kink too
  const Exact e = tent_fract(xd, sd);
  return std::fabs(static_cast<double>(q - R50(e.hi) - R50(e.lo)));
}

double check_box_compact(const std::string& f, double xd, double sd) {
  const R50 x = xd;
  const R50 hh = static_cast<R50>(compact_half_width(f, R100(xd), sqrt(R100(3)) * R100(sd)));
  const R50 q = quad([&](const R50& t) { return f_compact(f, t); }, x - hh, x + hh) / (2 * hh);
  const Exact e = box_compact(f, xd, sd);
  return std::fabs(static_cast<double>(q - R50(e.hi) - R50(e.lo)));
}

}  // namespace nb::ref
