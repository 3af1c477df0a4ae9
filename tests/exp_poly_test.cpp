// The exp-polynomial class in the generated table (issue 15): the catalog's Laplace bump
// exp(-|x|), exponential-decay pulse and x e^{-x} ramp against closed forms derived by hand
// (independent of the engine and of the runtime's algorithms), in double and float, at the hard
// inputs: at the kink/jump, tiny and huge sigma, huge |x|. The exhaustive quadrature comparison is
// blverify (verify_all).
#include <gtest/gtest.h>

#include <bandlimit/rules_clamped.hpp>
#include <bandlimit/table.hpp>
#include <cmath>

#include "exp_poly_refs.hpp"

namespace {

using namespace exp_refs;

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
      const double ref = gauss_ramp(x, s);
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
