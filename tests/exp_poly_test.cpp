// The exp-polynomial class in the generated table (issue 15): the catalog's Laplace bump
// exp(-|x|), exponential-decay pulse and x e^{-x} ramp against closed forms derived by hand
// (independent of the engine and of the runtime's algorithms), in double and float, at the hard
// inputs: at the kink/jump, tiny and huge sigma, huge |x|. The exhaustive quadrature comparison is
// blverify (verify_all).
#include <gtest/gtest.h>

#include <bandlimit/rules_clamped.hpp>
#include <bandlimit/table.hpp>
#include <cmath>

namespace {

using ld = long double;

// e^{u} erfc(v), v > 0, in long double (erfcl stays normal to v ~ 106); beyond, the asymptotic
// series e^{u - v^2}/(v sqrt(pi)) sum_j (-1)^j (2j-1)!!/(2v^2)^j (terms < 1e-30 by j = 8).
ld exp_erfc(ld u, ld v) {
  if (v < 100) return std::exp(u) * std::erfc(v);
  ld sum = 0, term = 1;
  for (int j = 0; j < 8; ++j) {
    sum += term;
    term *= -(2 * j + 1) / (2 * v * v);
  }
  return std::exp(u - v * v) / (v * std::sqrt(3.14159265358979323846L)) * sum;
}

// E[e^{-|x+U|}], U ~ N(0, s^2): e^{s^2/2} (e^{-x} Phic(s - x/s) + e^{x} Phic(s + x/s)).
double gauss_laplace(ld x, ld s) {
  const ld r = 1 / std::sqrt(2.0L);
  return double(0.5L * (exp_erfc(s * s / 2 - x, (s - x / s) * r) + exp_erfc(s * s / 2 + x, (s + x / s) * r)));
}
// e^{-|x|} sinhc(c)^n: the box (n = 1, c = h) and tent (n = 2, c = w/2) when the kernel misses 0.
// e^{-|x|} sinhc(c)^n, the exponentials merged for large c (sinh alone overflows).
ld decay_sinhc(ld x, ld c, int n) {
  if (c < 1e-4L) return std::exp(-std::abs(x)) * std::pow(1 + c * c / 6, n);
  if (c < 1) return std::exp(-std::abs(x)) * std::pow(std::sinh(c) / c, n);
  return std::exp(-std::abs(x) + n * (c - std::log(2 * c))) * std::pow(-std::expm1(-2 * c), n);
}
// (1/2h) int_{x-h}^{x+h} e^{-|t|} dt; straddling 0: (2 - e^{x-h}... ) from int_0^t e^{-|u|} = sgn(t)(1 -
// e^{-|t|}).
double box_laplace(ld x, ld s) {
  const ld h = std::sqrt(3.0L) * s;
  if (std::abs(x) >= h) return double(decay_sinhc(x, h, 1));
  return double((-std::expm1(-(x + h)) - std::expm1(-(h - x))) / (2 * h));
}
// Tent: second difference of F2(t) = e^{-|t|} + |t| - 1 (F2'' = e^{-|t|}), F2 by its series
// t^2/2 - |t|^3/6 + ... where expm1(-|t|) + |t| would cancel; e^{-|x|} sinhc(w/2)^2 off the kink.
ld F2(ld t) {
  t = std::abs(t);
  if (t > 0.1L) return std::expm1(-t) + t;
  ld sum = 0, term = t * t / 2;
  for (int k = 2; k < 24; ++k) {
    sum += term;
    term *= -t / (k + 1);
  }
  return sum;
}
double tent_laplace(ld x, ld s) {
  const ld w = std::sqrt(6.0L) * s;
  if (std::abs(x) >= w) return double(decay_sinhc(x, w / 2, 2));
  return double((F2(x + w) - 2 * F2(x) + F2(x - w)) / (w * w));
}

double rel(double v, double ref) {
  return std::abs(v - ref) / std::max(1.0, std::abs(ref));
}

// Issue 15 measured box/tent laplace at x = 0, sigma = 0.01 as 1 (true 0.9914 for the box).
TEST(ExpPoly, LaplaceAtTheKink) {
  const double h = std::sqrt(3.0) * 0.01, w = std::sqrt(6.0) * 0.01;
  const double box_ref = -std::expm1(-h) / h, tent_ref = double(2 * F2(w) / (ld(w) * w));
  EXPECT_NEAR(box_ref, 0.99139, 1e-5);
  EXPECT_NEAR(bl::box::laplace(0.0, 0.01), box_ref, 1e-15);
  EXPECT_NEAR(bl::tent::laplace(0.0, 0.01), tent_ref, 1e-15);
  EXPECT_NEAR(bl::box::laplace(0.0f, 0.01f), box_ref, 2e-7);
  EXPECT_NEAR(bl::tent::laplace(0.0f, 0.01f), tent_ref, 2e-7);
}

TEST(ExpPoly, LaplaceMatchesClosedFormsAtHardInputs) {
  for (double x : {0.0, 1e-9, -1e-9, 1e-4, -0.5, 1.0, 3.7, -10.0, 1e3 + 0.3, -1e6 - 0.3})
    for (double s : {1e-12, 1e-8, 1e-4, 0.01, 0.3, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6}) {
      const float xf = float(x), sf = float(s);
      EXPECT_LE(rel(bl::gaussian::laplace(x, s), gauss_laplace(x, s)), 1e-12) << x << " " << s;
      EXPECT_LE(rel(bl::box::laplace(x, s), box_laplace(x, s)), 1e-12) << x << " " << s;
      EXPECT_LE(rel(bl::tent::laplace(x, s), tent_laplace(x, s)), 1e-12) << x << " " << s;
      EXPECT_LE(rel(bl::gaussian::laplace(xf, sf), gauss_laplace(xf, sf)), 2e-6) << x << " " << s;
      EXPECT_LE(rel(bl::box::laplace(xf, sf), box_laplace(xf, sf)), 2e-6) << x << " " << s;
      EXPECT_LE(rel(bl::tent::laplace(xf, sf), tent_laplace(xf, sf)), 2e-5) << x << " " << s;
    }
}

// The ramp r(t) = t e^{-t} (t >= 0) under a Gaussian: with mu = x - s^2,
// E = e^{s^2/2 - x} [mu Phic(-mu/s) + s phi(mu/s)]; huge sigma is where expanding about mu cancels.
TEST(ExpPoly, RampUnderAWideGaussian) {
  for (double x : {0.0, 1.0, -3.7, 10.0})
    for (double s : {0.3, 3.0, 30.0, 1e3, 1e4, 1e6}) {
      // Closed form rewritten about the piece end (no cancellation): int_0^inf t e^{-t} phi_s(t - x) dt
      // = phi(x/s)/s * int_0^inf t e^{-t (1 - x/s^2)} e^{-t^2/(2 s^2)} dt, the last integral by
      // Gauss-Laguerre-free series: sum_j (-1)^j (2j+1)! / (j! 2^j s^{2j} b^{2j+2}), b = 1 - x/s^2,
      // valid (asymptotic, b s >> 1) for s >= 30 here; smaller s use the mu form directly.
      double ref;
      if (s >= 30) {
        const double b = 1 - x / (s * s);
        double sum = 0, term = 1 / (b * b);  // j = 0: 1!/b^2
        for (int j = 0; j < 12; ++j) {
          sum += term;
          term *= -double((2 * j + 2) * (2 * j + 3)) / (2.0 * (j + 1) * s * s * b * b);
        }
        ref = std::exp(-0.5 * (x / s) * (x / s)) / (s * std::sqrt(2 * M_PI)) * sum;
      } else {
        const double mu = x - s * s;
        ref = std::exp(s * s / 2 - x) * (mu * 0.5 * std::erfc(-mu / s / std::sqrt(2.0)) +
                                         s * std::exp(-0.5 * (mu / s) * (mu / s)) / std::sqrt(2 * M_PI));
      }
      EXPECT_LE(rel(bl::gaussian::exp_ramp(x, s), ref), 1e-12) << x << " " << s;
      EXPECT_LE(rel(bl::gaussian::exp_ramp(float(x), float(s)), ref), 2e-6) << x << " " << s;
      EXPECT_GE(bl::gaussian::exp_ramp(float(x), float(s)), 0.0f);
    }
}

// The decay pulse's box at its jump, tiny sigma: half the pulse's height to first order,
// (1/2h) int_0^h e^{-t} dt = (1 - e^{-h})/(2h).
TEST(ExpPoly, DecayPulseAtItsJump) {
  for (double s : {1e-12, 1e-8, 1e-4, 0.01}) {
    const double h = std::sqrt(3.0) * s;
    EXPECT_NEAR(bl::box::exp_decay(0.0, s), -std::expm1(-h) / (2 * h), 1e-15);
    EXPECT_NEAR(bl::box::exp_decay(0.0f, float(s)), -std::expm1(-h) / (2 * h), 1e-7);
  }
}

// Issue 15 measured rule3 of a Laplace bump at sigma = 1000 as a mean of 500001 (true 8e-4): the
// Taylor rule now stays in f's range, with a variance inside Popoviciu's bound.
TEST(ExpPoly, Rule3StaysInTheRange) {
  for (double s : {10.0, 1000.0, 1e6}) {
    const auto r = bl::rule3::laplace(0.0, s);
    EXPECT_GE(r.mean, 0.0);
    EXPECT_LE(r.mean, 1.0);
    EXPECT_GE(r.var, 0.0);
    EXPECT_LE(r.var, 0.25);
  }
  const auto small = bl::rule3::laplace(2.0, 1e-3);  // the Taylor rule where it applies: e^{-2}(1 + s^2/2)
  EXPECT_NEAR(small.mean, std::exp(-2.0) * (1 + 0.5e-6), 1e-12);
}

}  // namespace
