// The Bernoulli mixture rule for selects (lower.cpp, bernoulli_mixtures) against an independent
// reference: 2D quadrature of the plain shader (suite bumps + Phong) over the pixel's Gaussian
// footprint in (u, v).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "compiler/evaluator.hpp"
#include "compiler/lower.hpp"
#include "dsl/math.hpp"
#include "shaders/effects.hpp"
#include "tests/runtime/one_pixel.hpp"

namespace bl {
namespace {

template <class S>
shaders::Inputs<S> inputs(S u, S v) {
  shaders::Inputs<S> in;
  in.u = u;
  in.v = v;
  in.time = S(0);
  in.view = {S(0.3), S(-0.2), S(0.933)};
  in.light = {S(0.4), S(0.3), S(0.87)};
  return in;
}

const shaders::Effects kFx{shaders::Parallax::Bumps, shaders::Lighting::Phong};

// Red channel of a grey surface (albedo 0.5) with bumps and Phong.
template <class S>
S shade(S u, S v) {
  const shaders::Inputs<S> in = inputs(u, v);
  const shaders::Surface<S> s = shaders::bumps(in);
  return shaders::light(dsl::Vec3<S>{S(0.5), S(0.5), S(0.5)}, s, in, kFx).x;
}

ir::Graph bumps_graph() {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
  g.add_output("r", shade(u, v).id());
  return g;
}

// One pixel, u ~ N(mu, s^2), v ~ N(mv, s^2), orthogonal screen gradients (independent).
float run(const ir::Graph& g, const std::string& rule, float mu, float mv, float s) {
  const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
  return testing::run_one_pixel(p, {mu, mv}, {s, s}, {s / 0.5f, 0}, {0, s / 0.5f});
}

// E[shade(U, V)] by the midpoint rule on +-6 s in each axis (n^2 points).
double expect2(double mu, double mv, double s, int n = 400) {
  double sum = 0, wsum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double zu = -6 + (i + 0.5) * 12.0 / n, zv = -6 + (j + 0.5) * 12.0 / n;
      const double w = std::exp(-0.5 * (zu * zu + zv * zv));
      sum += w * shade<double>(mu + s * zu, mv + s * zv);
      wsum += w;
    }
  return sum / wsum;
}

ir::Graph one_input(const std::function<dsl::Var(dsl::Var)>& f) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true);
  g.add_output("r", f(u).id());
  return g;
}

float run1(const ir::Graph& g, float mu, float s) {
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  return testing::run_one_pixel(p, {mu}, {s}, {s / 0.5f}, {0});
}

double Phi(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

TEST(BernoulliMixture, ConstantBranchesAreExact) {
  // exp(2 select(u < 0.3, 1, -1)): p e^2 + (1 - p) e^-2, p = Phi((0.3 - m) / s). One lobe of mean
  // 2p - 1 through exp is not (at p = 1/2: exp of a two-point value's moments).
  const ir::Graph g = one_input([](dsl::Var u) {
    return dsl::exp(dsl::select(dsl::less(u, dsl::Var(0.3)), dsl::Var(1.0), dsl::Var(-1.0)) * 2.0);
  });
  for (double m : {0.3, 0.25, 0.4, -2.0, 5.0})
    for (double s : {1e-4, 0.05, 1.0, 100.0}) {
      const double p = Phi((0.3 - m) / s), want = p * std::exp(2.0) + (1 - p) * std::exp(-2.0);
      EXPECT_NEAR(run1(g, static_cast<float>(m), static_cast<float>(s)), want, 2e-5 * std::exp(2.0))
          << "m " << m << " s " << s;
    }
}

TEST(BernoulliMixture, ABranchSeesItsOperandTruncated) {
  // min(u, t)^2 written as a select: p E[U^2 | U < t] + (1 - p) t^2, the truncated normal's moments,
  // against quadrature (hard inputs: at the threshold, far on either side, tiny and huge s).
  const double t = 0.3;
  const ir::Graph g = one_input([&](dsl::Var u) {
    const dsl::Var m = dsl::select(dsl::less(u, dsl::Var(t)), u, dsl::Var(t));
    return m * m;
  });
  for (double mu : {0.3, 0.25, 0.35, -1.0, 2.0})
    for (double s : {1e-3, 0.05, 0.5}) {
      const int n = 200000;
      double sum = 0, wsum = 0;
      for (int i = 0; i < n; ++i) {
        const double z = -10 + (i + 0.5) * 20.0 / n, w = std::exp(-0.5 * z * z), x = std::min(mu + s * z, t);
        sum += w * x * x;
        wsum += w;
      }
      const double want = sum / wsum;
      EXPECT_NEAR(run1(g, static_cast<float>(mu), static_cast<float>(s)), want, 1e-4 * (1 + want))
          << "mu " << mu << " s " << s;
    }
}

TEST(BernoulliMixture, BumpRimsMatchQuadrature) {
  // Footprints across a cap's rim (|fu, fv| = R at u = 0.45, v = 0.27): the cap's and the flat
  // normal lit separately and mixed. Merged into one mean normal the error was 0.07-0.3 here.
  const ir::Graph g = bumps_graph();
  for (double s : {0.005, 0.02, 0.05})
    for (double mu : {0.44, 0.45, 0.46}) {
      const double want = expect2(mu, 0.27, s);
      EXPECT_NEAR(run(g, "gaussian", static_cast<float>(mu), 0.27f, static_cast<float>(s)), want, 0.015)
          << "mu " << mu << " s " << s;
    }
  // Inside a cap, away from the rim, no mixing: the plain shader's value.
  EXPECT_NEAR(run(g, "gaussian", 0.25f, 0.27f, 0.001f), shade<double>(0.25, 0.27), 2e-3);
}

}  // namespace
}  // namespace bl
