// The bivariate rules and Rule 2 as a user calls them: the product variance against Monte Carlo
// (and the misprinted eq. 4.9 of Yang & Barnes 2018 shown wrong), Clark's max, Li's exp example,
// conventions (NaN on bad input, sigma = 0), float/double agreement. blverify checks every rule
// against Monte Carlo / an independent mode reference; these tests use formulas from the papers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bandlimit/rules_bivariate.hpp"
#include "bandlimit/rules_mode.hpp"

namespace {

double Phi(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}
double phi(double z) {
  return std::exp(-z * z / 2) / std::sqrt(2 * M_PI);
}

struct Mc {
  double mean, var, se_mean, se_var;
};

// 10^6 samples of A B for A, B jointly normal; standard errors from the samples.
Mc mc_product(double ma, double sa, double mb, double sb, double rho) {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n01;
  const long n = 1000000;
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  std::vector<double> y(n);
  for (long i = 0; i < n; ++i) {
    const double z1 = n01(rng), z2 = n01(rng);
    y[i] = (ma + sa * z1) * (mb + sb * (rho * z1 + std::sqrt(1 - rho * rho) * z2));
    s1 += y[i];
  }
  const double m = s1 / n;
  for (double v : y) {
    const double d = v - m;
    s2 += d * d;
    s4 += d * d * d * d;
  }
  (void)s3;
  const double var = s2 / n;
  return {m, var, std::sqrt(var / n), std::sqrt((s4 / n - var * var) / n)};
}

// Yang & Barnes 2018 eq. 4.9 as printed, and with the typo corrected (sb^2, sa^2).
double var_printed(double ma, double sa, double mb, double sb, double r) {
  return ma * ma * sb + sa * mb * mb + 2 * r * ma * mb * sa * sb + sa * sa * sb * sb * (1 + r * r);
}
double var_corrected(double ma, double sa, double mb, double sb, double r) {
  return ma * ma * sb * sb + sa * sa * mb * mb + 2 * r * ma * mb * sa * sb + sa * sa * sb * sb * (1 + r * r);
}

TEST(Bivariate, ProductVarianceMatchesMonteCarloAndEq49AsPrintedDoesNot) {
  struct C {
    double ma, sa, mb, sb, rho;
  };
  for (C c : {C{2.0, 0.5, 3.0, 0.2, 0.4}, C{-1.5, 0.3, 4.0, 0.5, -0.9}, C{1.0, 3.0, 0.5, 0.1, 0.0}}) {
    const Mc m = mc_product(c.ma, c.sa, c.mb, c.sb, c.rho);
    const bl::stat<double> r = bl::bivariate::mul(c.ma, c.sa, c.mb, c.sb, c.rho);
    EXPECT_NEAR(r.mean, m.mean, 5 * m.se_mean);
    EXPECT_NEAR(r.var, m.var, 5 * m.se_var);
    EXPECT_NEAR(var_corrected(c.ma, c.sa, c.mb, c.sb, c.rho), m.var, 5 * m.se_var);
    EXPECT_GT(std::abs(var_printed(c.ma, c.sa, c.mb, c.sb, c.rho) - m.var), 50 * m.se_var)
        << "eq. 4.9 as printed agrees with Monte Carlo at ma=" << c.ma;
  }
}

// Clark (1961): E[max] = ma Phi(a) + mb Phi(-a) + th phi(a), E[max^2] = (ma^2 + sa^2) Phi(a) +
// (mb^2 + sb^2) Phi(-a) + (ma + mb) th phi(a), th^2 = sa^2 + sb^2 - 2 rho sa sb, a = (ma - mb)/th.
TEST(Bivariate, MaxAndMinAgreeWithClark) {
  for (double rho : {-0.9, 0.0, 0.5})
    for (double ma : {-1.0, 0.2, 3.0}) {
      const double sa = 0.7, mb = 0.4, sb = 1.3;
      const double th = std::sqrt(sa * sa + sb * sb - 2 * rho * sa * sb), a = (ma - mb) / th;
      const double e1 = ma * Phi(a) + mb * Phi(-a) + th * phi(a);
      const double e2 =
          (ma * ma + sa * sa) * Phi(a) + (mb * mb + sb * sb) * Phi(-a) + (ma + mb) * th * phi(a);
      const bl::stat<double> mx = bl::bivariate::max(ma, sa, mb, sb, rho);
      EXPECT_NEAR(mx.mean, e1, 1e-12 * (1 + std::abs(e1)));
      EXPECT_NEAR(mx.var, e2 - e1 * e1, 1e-11 * (1 + e2));
      // min = A + B - max; E[min^2] = E[A^2] + E[B^2] - E[max^2].
      const bl::stat<double> mn = bl::bivariate::min(ma, sa, mb, sb, rho);
      const double m1 = ma + mb - e1, m2 = ma * ma + sa * sa + mb * mb + sb * sb - e2;
      EXPECT_NEAR(mn.mean, m1, 1e-12 * (1 + std::abs(m1)));
      EXPECT_NEAR(mn.var, m2 - m1 * m1, 1e-11 * (1 + m2));
    }
}

TEST(Bivariate, ComparisonsAreNormalCdfOfTheDifference) {
  const bl::stat<double> l = bl::bivariate::less(0.3, 0.4, 1.0, 0.3, 0.2);
  const double p = Phi(0.7 / std::sqrt(0.16 + 0.09 - 2 * 0.2 * 0.12));
  EXPECT_NEAR(l.mean, p, 1e-15);
  EXPECT_NEAR(l.var, p * (1 - p), 1e-15);
  EXPECT_NEAR(bl::bivariate::greater(0.3, 0.4, 1.0, 0.3, 0.2).mean, 1 - p, 1e-15);
  EXPECT_EQ(bl::bivariate::less(0.0, 0.0, 1.0, 0.0, 0.0).mean, 1.0);  // constants: step of the difference
  EXPECT_EQ(bl::bivariate::less(1.0, 0.0, 1.0, 0.0, 0.0).mean, 0.0);  // step(0) = 0
}

// less and greater run in float (no double detour): against long double P(B - A > 0) over a grid with
// the hard inputs (|t| up to 1e6 and 14, beyond and near the table's reach; rho = +-1; sa = sb, so
// B - A's spread cancels to 0 at rho = 1; sigmas 1e-20 to 1e15; means 1e6 apart) within
// 1e-6 (1 + t^2) relative (t rounded to float: Phi's relative condition number in its tail is ~t^2)
// plus 1e-7 absolute (the normal table's Phic, which the float form reads: absolute, not relative,
// in the tail, as for the table entries; beyond tail_cut = 9 sd the small side, < 1e-19, is 0).
TEST(Bivariate, FloatComparisonsMatchLongDouble) {
  int bad = 0, n = 0;
  auto Phi_ld = [](long double z) { return 0.5L * std::erfc(-z / std::sqrt(2.0L)); };
  for (float ma : {-1e6f, -3.0f, 0.0f, 0.25f, 1.0f, 1e6f})
    for (float mb : {-2.5f, 0.0f, 0.3f, 1.0f, 7.0f})
      for (float sa : {0.0f, 1e-20f, 0.1f, 0.4f, 1.0f, 1e15f})
        for (float sb : {0.0f, 0.1f, 0.4f, 2.0f})
          for (float rho : {-1.0f, -0.3f, 0.0f, 0.9f, 1.0f}) {
            const long double s2 = (long double)(sb - sa) * (sb - sa) + 2.0L * (1.0L - rho) * sa * sb;
            const long double d = (long double)mb - ma;
            const long double p = s2 > 0 ? Phi_ld(d / std::sqrt(s2)) : (d > 0 ? 1.0L : 0.0L);
            const long double want_var = s2 > 0 ? p * Phi_ld(-d / std::sqrt(s2)) : 0.0L;
            for (int greater = 0; greater < 2; ++greater) {
              const bl::stat<float> f = greater ? bl::bivariate::greater(ma, sa, mb, sb, rho)
                                                : bl::bivariate::less(ma, sa, mb, sb, rho);
              long double want = greater ? (s2 > 0 ? Phi_ld(-d / std::sqrt(s2)) : (d < 0 ? 1.0L : 0.0L)) : p;
              const long double t = s2 > 0 ? d / std::sqrt(s2) : 0.0L;
              for (auto [got, ref] : {std::pair<long double, long double>{f.mean, want}, {f.var, want_var}}) {
                ++n;
                if (!(std::fabs(got - ref) <= 1e-6L * (1 + t * t) * std::fabs(ref) + 1e-7L) && bad++ < 5)
                  ADD_FAILURE() << (greater ? "greater" : "less") << "(" << ma << ", " << sa << ", " << mb
                                << ", " << sb << ", " << rho << "): " << (double)got << " vs " << (double)ref;
              }
            }
          }
  EXPECT_EQ(bad, 0) << "of " << n;
}

TEST(Bivariate, BadInputGivesNaNAndSigmaZeroIsExact) {
  const double nan = std::nan("");
  for (auto r : {bl::bivariate::add(1.0, -0.1, 2.0, 0.1, 0.0), bl::bivariate::mul(1.0, 0.1, 2.0, nan, 0.0),
                 bl::bivariate::max(1.0, 0.1, 2.0, 0.1, 1.5), bl::bivariate::div(1.0, 0.1, 2.0, 0.1, nan),
                 bl::bivariate::select(0.5, -1.0, 1.0, 0.1, 2.0, 0.1), bl::bivariate::mod(1.0, nan, 2.0),
                 bl::bivariate::mod(1.0, 0.1, 0.0), bl::rule2::exp(0.0, -1.0), bl::rule2::tan(0.3, nan)}) {
    EXPECT_TRUE(std::isnan(r.mean));
    EXPECT_TRUE(std::isnan(r.var));
  }
  const bl::stat<double> m = bl::bivariate::mul(1.5, 0.0, -2.0, 0.0, 0.3);
  EXPECT_EQ(m.mean, -3.0);
  EXPECT_EQ(m.var, 0.0);
  const bl::stat<double> d = bl::bivariate::mod(7.25, 0.0, 2.0);
  EXPECT_EQ(d.mean, 1.25);
  EXPECT_EQ(d.var, 0.0);
  for (double mu : {-2.0, 0.5, 3.0}) {
    EXPECT_EQ(bl::rule2::tanh(mu, 0.0).mean, std::tanh(mu));
    EXPECT_EQ(bl::rule2::abs(mu, 0.0).mean, std::abs(mu));
    EXPECT_EQ(bl::rule2::inv(mu, 0.0).mean, 1 / mu);
  }
}

// Li et al. 2020 eqs. 14-15: Y = exp(X): mY = exp(mu - sigma^2), sY = mY sigma exp(sigma^2 / 2).
TEST(Rule2, ExpIsLiEquations14And15) {
  for (double mu : {-2.0, 0.0, 1.5})
    for (double s : {0.1, 0.5, 1.0}) {
      const bl::stat<double> r = bl::rule2::exp(mu, s);
      const double my = std::exp(mu - s * s), sy = my * s * std::exp(s * s / 2);
      EXPECT_NEAR(r.mean, my, 1e-15 * my);
      EXPECT_NEAR(r.var, sy * sy, 1e-14 * sy * sy);
    }
}

// Y = log(X): the mode equation x^2 - mu x - sigma^2 = 0 (a quadratic, no Lambert W), so
// mY = log((mu + sqrt(mu^2 + 4 sigma^2)) / 2) and sY = sigma / x* exp((x* - mu)^2 / (2 sigma^2)).
TEST(Rule2, LogModeIsTheQuadraticRoot) {
  for (double mu : {-1.0, 0.5, 3.0})
    for (double s : {0.05, 0.5}) {
      const double x = (mu + std::sqrt(mu * mu + 4 * s * s)) / 2;
      const double sy = s / x * std::exp((x - mu) * (x - mu) / (2 * s * s));
      const bl::stat<double> r = bl::rule2::log(mu, s);
      EXPECT_NEAR(r.mean, std::log(x), 1e-13);
      EXPECT_NEAR(std::sqrt(r.var), sy, 1e-12 * sy);
    }
}

// Rule 2 in float (closed forms run in float where the variance's factors are in float's range,
// the rest in double) against the double entry at the same float inputs, over hard inputs: mu at 0,
// tiny, huge and both signs, sigma from 0 to 1e6. Bound: blverify's float bound 2e-5 (mean relative
// to max(1, |mean|), variance relative to itself where it is a normal float); NaN where double has it.
TEST(Rule2, FloatWithin2e5OfDouble) {
  int nr = 0;
  const auto* rd = bl::registry::rule2_entries<double>(&nr);
  const auto* rf = bl::registry::rule2_entries<float>(&nr);
  std::vector<float> mus = {0.0f};
  for (float m : {1e-30f, 1e-6f, 0.01f, 0.3f, 0.999f, 1.0f, 1.57f, 3.0f, 30.0f, 1e3f, 1e5f, 1e10f}) {
    mus.push_back(m);
    mus.push_back(-m);
  }
  const std::vector<float> sigmas = {0.0f, 1e-30f, 1e-12f, 1e-6f, 1e-3f, 0.05f,
                                     0.3f, 1.0f,   3.0f,   30.0f, 1e3f,  1e6f};
  for (int i = 0; i < nr; ++i) {
    int bad = 0, compared = 0;
    for (float mu : mus)
      for (float s : sigmas) {
        const bl::stat<double> d = rd[i].fn(mu, s);
        const bl::stat<float> f = rf[i].fn(mu, s);
        if (std::isnan(d.mean) || std::isnan(d.var)) {
          bad += !(std::isnan(f.mean) || std::isnan(f.var));
          continue;
        }
        bool ok =
            std::fabs(f.mean - d.mean) <= 2e-5 * std::max(1.0, std::fabs(d.mean)) || std::fabs(d.mean) > 3e38;
        if (d.var >= 1e-37 && d.var <= 3e38) ok &= std::fabs(f.var - d.var) <= 2e-5 * d.var;
        ++compared;
        if (!ok && bad++ < 4)
          ADD_FAILURE() << rd[i].cpp << " mu=" << mu << " sigma=" << s << ": float {" << f.mean << ", "
                        << f.var << "} double {" << d.mean << ", " << d.var << "}";
      }
    EXPECT_EQ(bad, 0) << rd[i].cpp;
    EXPECT_GT(compared, 100) << rd[i].cpp;
  }
}

TEST(Rules, FloatAndDoubleAgreeAndRegistriesAreComplete) {
  int nb = 0, nr = 0, nbf = 0, nrf = 0;
  const auto* bd = bl::registry::binary_entries<double>(&nb);
  const auto* bf = bl::registry::binary_entries<float>(&nbf);
  const auto* rd = bl::registry::rule2_entries<double>(&nr);
  const auto* rf = bl::registry::rule2_entries<float>(&nrf);
  ASSERT_EQ(nb, 8);
  ASSERT_EQ(nb, nbf);
  ASSERT_GE(nr, 8);
  ASSERT_EQ(nr, nrf);
  for (int i = 0; i < nb; ++i) {
    const bl::stat<double> d = bd[i].fn(0.7, 0.3, 1.1, 0.4, 0.25);
    const bl::stat<float> f = bf[i].fn(0.7f, 0.3f, 1.1f, 0.4f, 0.25f);
    EXPECT_NEAR(f.mean, d.mean, 1e-6 * (1 + std::abs(d.mean))) << bd[i].cpp;
    EXPECT_NEAR(f.var, d.var, 1e-6 * (1 + d.var)) << bd[i].cpp;
  }
  for (int i = 0; i < nr; ++i) {
    EXPECT_EQ(std::string(rd[i].rule), "rule2");
    const bl::stat<double> d = rd[i].fn(0.6, 0.2);
    const bl::stat<float> f = rf[i].fn(0.6f, 0.2f);
    EXPECT_TRUE(std::isfinite(d.mean) && d.var > 0) << rd[i].cpp;
    EXPECT_NEAR(f.mean, d.mean, 1e-6 * (1 + std::abs(d.mean))) << rd[i].cpp;
    EXPECT_NEAR(f.var, d.var, 1e-6 * (1 + d.var)) << rd[i].cpp;
  }
}

}  // namespace
