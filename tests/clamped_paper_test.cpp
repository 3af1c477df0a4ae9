// The analytic examples of Li et al. 2020 (clamped domain), composed from the generated rules
// (notebooks_cpp/clamped_paper/examples/, shared with the clamped_paper notebook that reports them:
// docs/notebooks/clamped_paper.md), checked against the quadrature reference and the paper's claims.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "paper_examples.hpp"

namespace {

namespace cp = clamped_paper;

double mse_of(const cp::Example& e, const cp::Evaluation& r, const std::string& key) {
  for (std::size_t i = 0; i < e.methods.size(); ++i)
    if (e.methods[i].key == key) return r.mse[i];
  ADD_FAILURE() << e.title << ": no method " << key;
  return NAN;
}

TEST(ClampedPaper, ReferenceMatchesClosedForm) {
  // E[exp(-X^2)] = exp(-mu^2/(1+2s^2))/sqrt(1+2s^2).
  const double s = 0.5;
  for (double mu : {-2.0, 0.3, 1.7}) {
    const double cf = std::exp(-mu * mu / (1 + 2 * s * s)) / std::sqrt(1 + 2 * s * s);
    EXPECT_NEAR(cp::truth([](double x) { return std::exp(-x * x); }, mu, s), cf, 1e-13);
  }
}

// Table 1's ordering: Rule 1 beats the unclamped adaptive rule and Yang-fract on all three functions.
TEST(ClampedPaper, Table1Ordering) {
  const auto mus = cp::grid(cp::kMuLo, cp::kMuHi, cp::kMuN);
  for (const cp::Example& e : cp::table1()) {
    const cp::Evaluation r = cp::evaluate(e, mus);
    for (const double m : r.mse) EXPECT_TRUE(std::isfinite(m)) << e.title;
    EXPECT_LT(mse_of(e, r, "rule1"), mse_of(e, r, "adaptive")) << e.title;
    EXPECT_LT(mse_of(e, r, "rule1"), mse_of(e, r, "yang_fract")) << e.title;
  }
}

// Figure 2: at sigma^2 = 1/2 the adaptive rule is the constant exp(-1/4) for every mu.
TEST(ClampedPaper, Figure2AdaptiveIsConstant) {
  const cp::Example e = cp::figure2();
  ASSERT_EQ(e.methods.front().key, "adaptive");
  for (const double mu : cp::grid(cp::kMuLo, cp::kMuHi, cp::kMuN))
    EXPECT_NEAR(e.methods.front().approx(mu), std::exp(-0.25), 1e-12) << mu;
}

TEST(ClampedPaper, Figure4RulesBeatAdaptive) {
  int steps = 0;
  const cp::Example e = cp::figure4(&steps);
  const cp::Evaluation r = cp::evaluate(e, cp::grid(cp::kMuLo, cp::kMuHi, cp::kMuN));
  for (const double m : r.mse) EXPECT_TRUE(std::isfinite(m));
  EXPECT_LT(mse_of(e, r, "rule1"), mse_of(e, r, "adaptive"));
  EXPECT_LT(mse_of(e, r, "rule3"), mse_of(e, r, "adaptive"));
  EXPECT_GT(steps, 0);
  EXPECT_LE(steps, 40);  // the solver's cap
}

// Figure 3: Rule 1's renormalized Gaussian keeps the adaptive mean and variance; Rule 2 is eqs. 14-15.
TEST(ClampedPaper, Figure3Fits) {
  const cp::Figure3 f = cp::figure3();
  EXPECT_NEAR(f.rule1_tm.mean, f.adaptive.mean, 1e-9);
  EXPECT_NEAR(f.rule1_tm.var, f.adaptive.var, 1e-9);
  const double s = f.sigma, my = std::exp(-s * s);
  EXPECT_NEAR(f.rule2.mean, my, 1e-14);
  EXPECT_NEAR(std::sqrt(f.rule2.var), my * s / std::exp(-s * s / 2), 1e-14);
  for (const char* k : {"adaptive", "rule1", "rule2"}) EXPECT_TRUE(std::isfinite(cp::density_mse(f, k))) << k;
}

}  // namespace
