// Closed forms of the Laplace bump e^{-|x|} smoothed by the three kernels, written by hand from
// the definitions (independent of the engine and the runtime), in long double with the
// cancellations of the naive forms avoided. Shared by exp_poly_test and support_exp_test.
#pragma once

#include <algorithm>
#include <cmath>

namespace exp_refs {

using ld = long double;

// e^{u} erfc(v), v > 0, in long double (erfcl stays normal to v ~ 106); beyond, the asymptotic
// series e^{u - v^2}/(v sqrt(pi)) sum_j (-1)^j (2j-1)!!/(2v^2)^j (terms < 1e-30 by j = 8).
inline ld exp_erfc(ld u, ld v) {
  if (v < 100) return std::exp(u) * std::erfc(v);
  ld sum = 0, term = 1;
  for (int j = 0; j < 8; ++j) {
    sum += term;
    term *= -(2 * j + 1) / (2 * v * v);
  }
  return std::exp(u - v * v) / (v * std::sqrt(3.14159265358979323846L)) * sum;
}

// E[e^{-|x+U|}], U ~ N(0, s^2): e^{s^2/2} (e^{-x} Phic(s - x/s) + e^{x} Phic(s + x/s)).
inline double gauss_laplace(ld x, ld s) {
  const ld r = 1 / std::sqrt(2.0L);
  return double(0.5L * (exp_erfc(s * s / 2 - x, (s - x / s) * r) + exp_erfc(s * s / 2 + x, (s + x / s) * r)));
}
// e^{-|x|} sinhc(c)^n: the box (n = 1, c = h) and tent (n = 2, c = w/2) when the kernel misses 0.
// e^{-|x|} sinhc(c)^n, the exponentials merged for large c (sinh alone overflows).
inline ld decay_sinhc(ld x, ld c, int n) {
  if (c < 1e-4L) return std::exp(-std::abs(x)) * std::pow(1 + c * c / 6, n);
  if (c < 1) return std::exp(-std::abs(x)) * std::pow(std::sinh(c) / c, n);
  return std::exp(-std::abs(x) + n * (c - std::log(2 * c))) * std::pow(-std::expm1(-2 * c), n);
}
// (1/2h) int_{x-h}^{x+h} e^{-|t|} dt; straddling 0: (2 - e^{x-h}... ) from int_0^t e^{-|u|} = sgn(t)(1 -
// e^{-|t|}).
inline double box_laplace(ld x, ld s) {
  const ld h = std::sqrt(3.0L) * s;
  if (std::abs(x) >= h) return double(decay_sinhc(x, h, 1));
  return double((-std::expm1(-(x + h)) - std::expm1(-(h - x))) / (2 * h));
}
// Tent: second difference of F2(t) = e^{-|t|} + |t| - 1 (F2'' = e^{-|t|}), F2 by its series
// t^2/2 - |t|^3/6 + ... where expm1(-|t|) + |t| would cancel; e^{-|x|} sinhc(w/2)^2 off the kink.
inline ld F2(ld t) {
  t = std::abs(t);
  if (t > 0.1L) return std::expm1(-t) + t;
  ld sum = 0, term = t * t / 2;
  for (int k = 2; k < 24; ++k) {
    sum += term;
    term *= -t / (k + 1);
  }
  return sum;
}
inline double tent_laplace(ld x, ld s) {
  const ld w = std::sqrt(6.0L) * s;
  if (std::abs(x) >= w) return double(decay_sinhc(x, w / 2, 2));
  return double((F2(x + w) - 2 * F2(x) + F2(x - w)) / (w * w));
}

// The ramp t e^{-t} (t >= 0) under N(0, s^2) at x. s < 30: with mu = x - s^2,
// e^{s^2/2 - x} [mu Phic(-mu/s) + s phi(mu/s)]. s >= 30 (where that form cancels): about the piece
// end, phi(x/s)/s int_0^inf t e^{-b t} e^{-t^2/(2 s^2)} dt with b = 1 - x/s^2, by the asymptotic
// series sum_j (-1)^j (2j+1)!/(j! 2^j s^{2j} b^{2j+2}) (12 terms, b s >> 1 here).
inline double gauss_ramp(double x, double s) {
  if (s >= 30) {
    const double b = 1 - x / (s * s);
    double sum = 0, term = 1 / (b * b);
    for (int j = 0; j < 12; ++j) {
      sum += term;
      term *= -double((2 * j + 2) * (2 * j + 3)) / (2.0 * (j + 1) * s * s * b * b);
    }
    return std::exp(-0.5 * (x / s) * (x / s)) / (s * std::sqrt(2 * M_PI)) * sum;
  }
  const double mu = x - s * s;
  return std::exp(s * s / 2 - x) * (mu * 0.5 * std::erfc(-mu / s / std::sqrt(2.0)) +
                                    s * std::exp(-0.5 * (mu / s) * (mu / s)) / std::sqrt(2 * M_PI));
}

inline double rel(double v, double ref) {
  return std::abs(v - ref) / std::max(1.0, std::abs(ref));
}

}  // namespace exp_refs
