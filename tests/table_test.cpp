// The generated table as a user links it: every registry entry in float and double obeys the
// conventions (sigma = 0 gives f, bad sigma gives NaN), and selected entries match closed forms
// from the literature. The exhaustive comparison with quadrature is blverify (test verify_all).
#include "bandlimit/table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bandlimit/registry.hpp"

namespace {

bool at_break(const bl::registry::AtomicInfo& a, double x) {
  for (int i = 0; i < a.nbreaks; ++i) {
    double b = a.breaks[i];
    if (a.period > 0) b += a.period * std::round((x - b) / a.period);
    if (std::abs(x - b) < 1e-12) return true;
  }
  return false;
}

TEST(Table, SigmaZeroGivesTheFunctionAndBadSigmaGivesNaN) {
  int n = 0;
  const auto* e = bl::registry::entries<double>(&n);
  ASSERT_GT(n, 150);
  for (int i = 0; i < n; ++i) {
    const auto& en = e[i];
    for (double x : {0.3, -1.7, 2.2, 0.75}) {
      if (at_break(*en.atomic, x) || x <= en.atomic->domain_lo || x >= en.atomic->domain_hi) continue;
      double f = en.plain(x);
      if (en.rule == std::string("moment")) f = std::pow(x, en.order);
      if (en.squared) f *= f;
      EXPECT_NEAR(en.smoothed(x, 0.0), f, 1e-14 * std::max(1.0, std::abs(f))) << en.cpp << " x=" << x;
      EXPECT_TRUE(std::isnan(en.smoothed(x, -0.1))) << en.cpp;
      EXPECT_TRUE(std::isnan(en.smoothed(x, std::nan("")))) << en.cpp;
    }
  }
}

// The plain staircases are exact at their jumps too, where a plain program evaluates them on whole
// numbers (int(floor(y)) is trunc of a floor): the smoothed forms never see a measure-zero set, the
// plain ones do. trunc's identity x - fract(x) + 1 - step(x) gave 0 at x = -1.
template <class T>
void expect_staircases() {
  struct Row {
    T x, floor, ceil, trunc;
  };
  const Row rows[] = {{T(-3), T(-3), T(-3), T(-3)},
                      {T(-2.5), T(-3), T(-2), T(-2)},
                      {T(-1), T(-1), T(-1), T(-1)},
                      {T(-0.25), T(-1), T(0), T(0)},
                      {T(0), T(0), T(0), T(0)},
                      {T(0.75), T(0), T(1), T(0)},
                      {T(2), T(2), T(2), T(2)},
                      {T(7.5), T(7), T(8), T(7)},
                      {T(-1e6), T(-1e6), T(-1e6), T(-1e6)},
                      {T(-4097.5), T(-4098), T(-4097), T(-4097)}};
  for (const Row& r : rows) {
    EXPECT_EQ(bl::plain::floor(r.x), r.floor) << "floor(" << r.x << ")";
    EXPECT_EQ(bl::plain::ceil(r.x), r.ceil) << "ceil(" << r.x << ")";
    EXPECT_EQ(bl::plain::trunc(r.x), r.trunc) << "trunc(" << r.x << ")";
  }
}

TEST(Table, PlainStaircasesAreExactAtWholeNumbers) {
  expect_staircases<float>();
  expect_staircases<double>();
}

TEST(Table, FloatAndDoubleInstantiationsAgree) {
  int nd = 0, nf = 0;
  const auto* ed = bl::registry::entries<double>(&nd);
  const auto* ef = bl::registry::entries<float>(&nf);
  ASSERT_EQ(nd, nf);
  for (int i = 0; i < nd; ++i)
    for (float x : {0.3f, -1.2f, 2.6f})
      for (float s : {0.05f, 0.4f, 1.5f}) {
        if (x <= ed[i].atomic->domain_lo) continue;
        const double d = ed[i].smoothed(x, s);
        const float f = ef[i].smoothed(x, s);
        if (!std::isfinite(d)) continue;
        EXPECT_LE(std::abs(f - d) / std::max(1.0, std::abs(d)), 2e-5)
            << ed[i].cpp << " x=" << x << " s=" << s;
      }
}

// step under a Gaussian is the normal CDF; Dorn et al. Table 1.
TEST(Table, GaussianStepIsTheNormalCdf) {
  for (double x : {-40.0, -5.0, -0.1, 0.0, 1e-9, 0.7, 9.0})
    for (double s : {1e-8, 0.2, 1.0, 50.0}) {
      const double ref = 0.5 * std::erfc(-x / (s * std::sqrt(2.0)));
      EXPECT_NEAR(bl::gaussian::step(x, s), ref, 1e-15 + 1e-12 * ref) << x << " " << s;
    }
}

// fract under a Gaussian: Dorn et al.'s Fourier series (section 3.3), summed to convergence.
TEST(Table, GaussianFractMatchesDornFourierSeries) {
  for (double x : {-2.3, 0.0, 0.2, 0.5, 0.999, 17.25})
    for (double s : {0.08, 0.15, 0.3, 1.0}) {
      double ref = 0.5;
      for (int n = 1; n < 4000; ++n)
        ref -= std::sin(2 * M_PI * n * x) * std::exp(-2 * s * s * M_PI * M_PI * n * n) / (M_PI * n);
      EXPECT_NEAR(bl::gaussian::fract(x, s), ref, 1e-11) << x << " " << s;
      EXPECT_NEAR(bl::gaussian::floor(x, s), x - ref, 1e-11 * std::max(1.0, std::abs(x)));
    }
}

// fract_2 of Dorn et al. Table 1 is a box of width w (half-width w/2), i.e. sigma = w / (2 sqrt 3).
TEST(Table, BoxFractMatchesDornFract2) {
  auto fr = [](double t) { return t - std::floor(t); };
  for (double x : {-2.3, 0.0, 0.2, 0.5, 0.999, 17.25})
    for (double w : {0.05, 0.3, 1.0, 2.7}) {
      const double a = x + w / 2, b = x - w / 2;
      const double ref = (fr(a) * fr(a) + std::floor(a) - fr(b) * fr(b) - std::floor(b)) / (2 * w);
      EXPECT_NEAR(bl::box::fract(x, w / (2 * std::sqrt(3.0))), ref, 1e-12) << x << " " << w;
    }
}

}  // namespace

// Huge arguments in float (a footprint near the horizon: x ~ 3e7, sigma ~ 1e7 in uv units) once
// sent the box/tent periodic forms into an endless loop (a float period counter past 2^24 does not
// advance). Every convolution entry must return, and floor^2 must match the wide-kernel identity
// E[floor(X)^2] = E[X^2] - E[X] + 1/3 + O(1/x) (fract ~ U[0, 1) independent of X for sigma >> 1).
TEST(Table, HugeFloatArgumentsReturn) {
  int n = 0;
  const auto* e = bl::registry::entries<float>(&n);
  for (int i = 0; i < n; ++i) {
    const auto& en = e[i];
    if (en.rule != std::string("convolution")) continue;
    for (float x : {3e7f, -3e7f, 1e9f})
      for (float s : {1e7f, 4e8f}) (void)en.smoothed(x, s);  // must return (a hang fails by timeout)
  }
  const double x = 3e7, s = 1e7;
  const double want = x * x + s * s - x + 1.0 / 3;
  for (const char* name : {"bl::box::floor_sq", "bl::tent::floor_sq"})
    for (int i = 0; i < n; ++i)
      if (e[i].cpp == std::string(name)) {
        const double got = e[i].smoothed(static_cast<float>(x), static_cast<float>(s));
        EXPECT_NEAR(got, want, 1e-4 * want) << name;
      }
}
