// A periodic break that is not a binary number (issue 15): pulse30 is 1 on [0, 3/10) of each
// period 1, and 3/10 is no double or float. Near the break the smoothed value is a function of the
// exact distance d = 3/10 - x alone (the other breaks are >= 0.29 away, > 29 sigma here), so the
// references are the kernels' CDFs at d, with d formed exactly: 3 - 10 r (r = x mod 1, exact) is
// computed by one fma with no rounding at this cancellation, then divided by 10. Before the fix the
// tables saw the break at its rounded constant (0.3f is 1.2e-8 above 3/10): float was off by 0.38
// at sigma = 1e-8 and 5e-5 at sigma = 1e-4, double by 4e-6 at sigma = 1e-12.
#include <gtest/gtest.h>

#include <bandlimit/table.hpp>
#include <cmath>

namespace {

double dist(double x) {                // 3/10 - (x mod 1), for x mod 1 near 3/10
  const double r = x - std::floor(x);  // exact for these x (|x| <= 1e6 + 1, r near 0.3)
  return std::fma(-10.0, r, 3.0) / 10.0;
}
double gauss_ref(double d, double s) {
  return 0.5 * std::erfc(-d / (s * std::sqrt(2.0)));
}
double box_ref(double d, double s) {
  const double h = std::sqrt(3.0) * s;
  return std::fmin(1.0, std::fmax(0.0, (d + h) / (2 * h)));
}
double tent_ref(double d, double s) {  // P(U < d), U with density (w - |u|)/w^2 on [-w, w]
  const double w = std::sqrt(6.0) * s;
  if (d <= -w) return 0;
  if (d >= w) return 1;
  return d < 0 ? (w + d) * (w + d) / (2 * w * w) : 1 - (w - d) * (w - d) / (2 * w * w);
}

const double kX[] = {0.3,
                     std::nextafter(0.3, 1.0),
                     std::nextafter(0.3, 0.0),
                     0.3 + 1e-9,
                     0.3 - 1e-9,
                     0.3 + 1e-12,
                     0.3 - 1e-12,
                     0.3 + 1e-4,
                     0.3 - 1e-4,
                     1e6 + 0.3,
                     -1e6 + 0.3,
                     1e3 + 0.3,
                     -3.7,
                     2.3};
const double kS[] = {1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3};

TEST(PeriodicBreak, PlainIsOnTheExactSide) {
  EXPECT_EQ(bl::detail::gen::plain_pulse30<double>(0.3), 1.0);   // double(0.3) < 3/10
  EXPECT_EQ(bl::detail::gen::plain_pulse30<float>(0.3f), 0.0f);  // 0.3f > 3/10
  EXPECT_EQ(bl::gaussian::pulse30(0.3, 0.0), 1.0);
  EXPECT_EQ(bl::box::pulse30(0.3f, 0.0f), 0.0f);
  EXPECT_EQ(bl::tent::pulse30(-0.7, 0.0), 0.0);  // -0.7 (double) is above -7/10: x mod 1 > 3/10
  EXPECT_EQ(bl::tent::pulse30(-3.7, 0.0), 1.0);  // -3.7 (double) is below -37/10: x mod 1 < 3/10
}

TEST(PeriodicBreak, DoubleWithin1e9OfTheExactBreak) {
  for (double x : kX)
    for (double s : kS) {
      const double d = dist(x);
      ASSERT_LT(std::fabs(d), 1e-3) << x;
      EXPECT_NEAR(bl::gaussian::pulse30(x, s), gauss_ref(d, s), 1e-9) << x << " " << s;
      EXPECT_NEAR(bl::box::pulse30(x, s), box_ref(d, s), 1e-9) << x << " " << s;
      EXPECT_NEAR(bl::tent::pulse30(x, s), tent_ref(d, s), 1e-9) << x << " " << s;
      EXPECT_NEAR(bl::gaussian::pulse30_sq(x, s), gauss_ref(d, s), 1e-9) << x << " " << s;
    }
}

TEST(PeriodicBreak, FloatWithin2e5OfTheExactBreak) {
  for (double x0 : kX)
    for (double s0 : kS) {
      const float x = float(x0), s = float(s0);
      const double d = dist(x);
      if (!(std::fabs(d) < 1e-3)) continue;  // 1e6 + 0.3 rounds to 1e6 + 0.25 in float
      EXPECT_NEAR(bl::gaussian::pulse30(x, s), gauss_ref(d, s), 2e-5) << x0 << " " << s0;
      EXPECT_NEAR(bl::box::pulse30(x, s), box_ref(d, s), 2e-5) << x0 << " " << s0;
      EXPECT_NEAR(bl::tent::pulse30(x, s), tent_ref(d, s), 2e-5) << x0 << " " << s0;
    }
}

}  // namespace
