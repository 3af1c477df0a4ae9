// bl::deriv against 4th-order central differences (h = 1e-3, error ~1e-12 f^(5)) of the plain
// atomics (d1) and of d1 (d2), at points at least 0.05 away from every break and singularity.
#include <gtest/gtest.h>

#include <bandlimit/rules_clamped.hpp>
#include <cmath>
#include <string>

namespace {

template <class F>
double central_diff(F f, double x) {
  const double h = 1e-3;
  return (8 * (f(x + h) - f(x - h)) - (f(x + 2 * h) - f(x - 2 * h))) / (12 * h);
}
const bl::registry::Entry<double>* plain_of(const bl::registry::AtomicInfo* a) {
  int n = 0;
  const auto* e = bl::registry::entries<double>(&n);
  for (int i = 0; i < n; ++i)
    if (e[i].atomic == a) return &e[i];
  return nullptr;
}

// Too close to a break (repeating with the period) for a finite difference of width ~1e-2.
bool near_break(const bl::registry::AtomicInfo& a, double x) {
  for (int i = 0; i < a.nbreaks; ++i) {
    double d = x - a.breaks[i];
    if (a.period > 0) d -= a.period * std::round(d / a.period);
    if (std::abs(d) < 0.05) return true;
  }
  return x <= a.domain_lo + 0.05 || x >= a.domain_hi - 0.05;
}

TEST(Derivatives, MatchFiniteDifferences) {
  int n = 0;
  const auto* d = bl::registry::derivative_entries<double>(&n);
  ASSERT_GT(n, 0);
  int checked = 0;
  for (int i = 0; i < n; ++i) {
    const auto& a = *d[i].atomic;
    const auto* p = plain_of(d[i].atomic);
    ASSERT_NE(p, nullptr) << a.name;
    const bl::registry::DerivativeEntry<double>* d1 = d[i].order == 2 ? &d[i - 1] : nullptr;
    for (double x : {-2.7, -1.3, -0.4, 0.3, 0.77, 1.2, 2.45, 3.9}) {
      if (near_break(a, x)) continue;
      const double got = d[i].fn(x);
      double ref;
      if (d[i].order == 1)
        ref = central_diff(p->plain, x);
      else
        ref = central_diff(d1->fn, x);
      EXPECT_NEAR(got, ref, 1e-6 * std::max(1.0, std::abs(ref))) << d[i].cpp << " at " << x;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(Derivatives, PublicNamesAndBadInput) {
  EXPECT_DOUBLE_EQ(bl::deriv::sin_d1(0.5), std::cos(0.5));
  EXPECT_FLOAT_EQ(bl::deriv::exp_d2(1.0f), std::exp(1.0f));
  EXPECT_DOUBLE_EQ(bl::deriv::floor_d1(2.5), 0.0);
  EXPECT_DOUBLE_EQ(bl::deriv::fract_d1(-2.5), 1.0);
  EXPECT_DOUBLE_EQ(bl::deriv::abs_d1(-3.0), -1.0);
  EXPECT_DOUBLE_EQ(bl::deriv::inv2_d2(2.0), 6.0 / 16.0);
  EXPECT_TRUE(std::isnan(bl::deriv::log_d1(-1.0)));  // outside the domain
  EXPECT_TRUE(std::isnan(bl::deriv::sqrt_d2(-1.0f)));
}

}  // namespace

// A renormalized Gaussian narrower than the spacing of doubles at its centre (a point mass at the
// bound: centre 0.5 on [0, 0.5]) leaves the quadrature no node; expect() used to return 0/0. The
// exact value is the point mass g(0.5).
TEST(Rule1, PointMassAtABound) {
  for (double s : {1e-20, 1e-17, 1e-16, 1e-15, 1e-14}) {
    const bl::rule1::Params<double> p{0.5, s, 0};
    const auto r =
        bl::rule1::expect(bl::rule1::Kernel::gaussian, p, 0.0, 0.5, [](double u) { return std::sqrt(u); });
    EXPECT_NEAR(r.mean, std::sqrt(0.5), 1e-12) << "sigma " << s;
    EXPECT_NEAR(r.var, 0.0, 1e-20) << "sigma " << s;
  }
}
