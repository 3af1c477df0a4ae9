// The rules issue 13 added or changed, each against an independent reference (quadrature of the
// true expectation, closed forms), and a convergence test: as the footprint shrinks every rule
// tends to the plain shader.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "compiler/evaluator.hpp"
#include "compiler/lower.hpp"
#include "compiler/square_product.hpp"
#include "dsl/math.hpp"
#include "shaders/shader.hpp"
#include "tests/runtime/one_pixel.hpp"
#include "tests/runtime/quadrature.hpp"

namespace bl {
namespace {

ir::Graph one_input(const std::function<dsl::Var(dsl::Var)>& f) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true);
  g.add_output("r", f(u).id());
  return g;
}

// One pixel; the screen gradient of u is (s / 0.5, 0), i.e. a footprint of sd 0.5 px.
float run1(const ir::Graph& g, const std::string& rule, float mu, float sigma) {
  const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
  return testing::run_one_pixel(p, {mu}, {sigma}, {sigma / 0.5f}, {0});
}

// E[f(X)], X ~ N(mu, s^2), by the midpoint rule on +-10 s (f piecewise smooth: 2e5 points put the
// error far below the tolerances used here).
double expect(const std::function<double(double)>& f, double mu, double s) {
  return testing::gaussian_mean_1d(f, mu, s, 200000, 10);
}

double fract(double x) {
  return x - std::floor(x);
}

TEST(Rules, FractBeforeAWrapContinuousConsumerTakesTheDominantSide) {
  // pow2(fract(u) - 0.5) is continuous at fract's jumps: the mode rule applies.
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::pow2(dsl::fract(u) - 0.5); });
  const auto truth = [](double x) { return (fract(x) - 0.5) * (fract(x) - 0.5); };
  // Far from the jump with a narrow kernel it is the exact Gaussian rule: (f - 1/2)^2 + s^2.
  EXPECT_NEAR(run1(g, "gaussian", 3.3f, 0.01f), expect(truth, 3.3, 0.01), 1e-5);
  // At and next to the jump, narrow kernels (s <= 0.25 period, the pure mode): the composite's
  // true mean within 0.05 (the old rule averaged both sides to fract ~ 1/2: pow2 ~ 0.08 vs 0.25).
  for (double mu : {2.96, 2.99, 3.0, 3.01, 3.05})
    for (double s : {0.005, 0.02, 0.05, 0.1}) {
      const double want = expect(truth, mu, s);
      EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, 0.05)
          << "mu " << mu << " s " << s;
    }
  // Wide kernels blend into the full rule: E = 1/12 for s >> 1.
  EXPECT_NEAR(run1(g, "gaussian", 3.0f, 2.0f), 1.0 / 12, 1e-3);
  // fract read directly (an output sees the jump) keeps the full rule: 1/2 at the jump.
  const ir::Graph direct = one_input([](dsl::Var u) { return dsl::fract(u); });
  EXPECT_NEAR(run1(direct, "gaussian", 3.0f, 0.02f), expect(fract, 3.0, 0.02), 1e-4);
}

TEST(Rules, FloorVarianceDoesNotCancel) {
  // sin(100 floor(u)) reads floor's variance: E = sin(100 m) exp(-10^4 v / 2). At u = 40.7, sd 0.01
  // floor is 40 with certainty; a variance of 1.2e-4 (the old float cancellation) halves the result.
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::sin(dsl::floor(u) * 100.0); });
  EXPECT_NEAR(run1(g, "gaussian", 40.7f, 0.01f), std::sin(4000.0), 1e-3);
  const ir::Graph c = one_input([](dsl::Var u) { return dsl::sin(dsl::ceil(u) * 100.0); });
  EXPECT_NEAR(run1(c, "gaussian", 1040.7f, 0.01f), std::sin(104100.0), 1e-2);
  // Near a jump the shifted rule is still the Gaussian expectation of floor.
  const ir::Graph f = one_input([](dsl::Var u) { return dsl::floor(u); });
  EXPECT_NEAR(run1(f, "gaussian", 40.98f, 0.03f), expect([](double x) { return std::floor(x); }, 40.98, 0.03),
              2e-4);
}

TEST(Rules, IdenticalOperandsArePerfectlyCorrelated) {
  // E[X X] = m^2 + s^2 (rho = 0 gave m^2); X - X = 0; X / X = 1.
  const ir::Graph sq = one_input([](dsl::Var u) { return u * u; });
  EXPECT_NEAR(run1(sq, "gaussian", 0.7f, 0.3f), 0.49 + 0.09, 1e-6);
  const ir::Graph zero = one_input([](dsl::Var u) { return dsl::step(u - u + 0.1); });
  EXPECT_NEAR(run1(zero, "gaussian", 0.7f, 0.3f), 1.0, 1e-6);
  // Products of powers of one base use the exact moments: E[X^3] = m^3 + 3 m s^2,
  // E[X^4] = m^4 + 6 m^2 s^2 + 3 s^4 (pow2(X) pow2(X) and X X X X), E[X^5] via X pow4(X).
  const ir::Graph cube = one_input([](dsl::Var u) { return u * u * u; });
  EXPECT_NEAR(run1(cube, "gaussian", 0.7f, 0.3f), 0.343 + 3 * 0.7 * 0.09, 1e-5);
  const ir::Graph quart = one_input([](dsl::Var u) { return dsl::pow2(u) * dsl::pow2(u); });
  EXPECT_NEAR(run1(quart, "gaussian", 0.7f, 0.3f), 0.2401 + 6 * 0.49 * 0.09 + 3 * 0.0081, 1e-5);
  const ir::Graph fifth = one_input([](dsl::Var u) { return u * dsl::pow4(u); });
  EXPECT_NEAR(run1(fifth, "gaussian", 0.7f, 0.3f), expect([](double x) { return std::pow(x, 5); }, 0.7, 0.3),
              1e-5);
  // Var(X X) = 4 m^2 s^2 + 2 s^4 reaches the next rule: E[sin(X^2)] against quadrature.
  const ir::Graph sn = one_input([](dsl::Var u) { return dsl::sin(u * u); });
  const double want = expect([](double x) { return std::sin(x * x); }, 0.7, 0.05);
  EXPECT_NEAR(run1(sn, "gaussian", 0.7f, 0.05f), want, 2e-3);
}

TEST(Rules, OperandsOfOneRootAreCorrelated) {
  // step(u) step(2u) = step(u): E = Phi(m / s). Independence (rho forced to the constant 0) gives
  // Phi^2; the default rule (shared root u: Stein covariance) and rho=cov (screen gradients with
  // Stein slopes) must at least halve that error at and near the shared jump, and be near-exact far
  // from it.
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::step(u) * dsl::step(u * 2.0); });
  for (double mu : {-0.01, 0.0, 0.01}) {
    const double s = 0.02, want = 0.5 * std::erfc(-mu / (s * std::sqrt(2.0)));
    const float m = static_cast<float>(mu), sf = static_cast<float>(s);
    const double e0 = std::fabs(run1(g, "gaussian:rho=0.0", m, sf) - want);
    EXPECT_NEAR(e0, want - want * want, 1e-6);  // the independent product, as a check of the setup
    for (const char* rule : {"gaussian", "gaussian:rho=cov"})
      EXPECT_LT(std::fabs(run1(g, rule, m, sf) - want), 0.5 * e0) << rule << " mu " << mu;
  }
  EXPECT_NEAR(run1(g, "gaussian", 0.3f, 0.02f), 1.0, 1e-6);
  EXPECT_NEAR(run1(g, "gaussian:rho=cov", 0.3f, 0.02f), 1.0, 1e-6);
  // Affine functions of one base are perfectly correlated: (2 step(u) + 1) - step(u) = step(u) + 1
  // has the variance of step(u), Phi (1 - Phi); read through sin(10 .) against quadrature.
  const ir::Graph aff = one_input([](dsl::Var u) {
    const dsl::Var st = dsl::step(u);
    return dsl::sin((st * 2.0 + 1.0 - st) * 10.0);
  });
  const double p = 0.5 * std::erfc(-0.01 / (0.02 * std::sqrt(2.0))), v = p * (1 - p);
  const double want = std::sin(10 * (1 + p)) * std::exp(-50 * v);  // Gaussian rule on exact moments
  EXPECT_NEAR(run1(aff, "gaussian", 0.01f, 0.02f), want, 1e-4);
  EXPECT_EQ(rules::to_string(rules::parse_rule("gaussian:rho=cov")), "gaussian:rho=cov");
}

TEST(Rules, AHashOfAFloorIsAFiniteMixture) {
  // h(floor(u)) for a lattice hash h: E = sum_K P(floor = K) h(K), against quadrature of the plain
  // composite (the old rule smoothed the hash of a smoothed floor: ~1/2 whatever the cells hold).
  const auto h = [](double i) { return fract(std::sin(i * 1.7 + 0.3) * 13.37); };
  const ir::Graph g =
      one_input([](dsl::Var u) { return dsl::fract(dsl::sin(dsl::floor(u) * 1.7 + 0.3) * 13.37); });
  for (double mu : {3.02, 3.5, 3.97, -7.4})
    for (double s : {0.01, 0.05, 0.2}) {
      const double want = expect([&](double x) { return h(std::floor(x)); }, mu, s);
      EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, 1e-4)
          << "mu " << mu << " s " << s;
    }
  // The mixture's variance reaches the next rule: sin(6 h) against quadrature (the Gaussian rule on
  // the mixture's two moments: exact only for a narrow footprint inside one cell).
  const ir::Graph g2 = one_input(
      [](dsl::Var u) { return dsl::sin(dsl::fract(dsl::sin(dsl::floor(u) * 1.7 + 0.3) * 13.37) * 6.0); });
  EXPECT_NEAR(run1(g2, "gaussian", 3.5f, 0.01f), std::sin(6 * h(3)), 1e-4);
}

TEST(Rules, ALatticeMixturesVarianceDoesNotCancel) {
  // sin(31.17 floor(u) + 0.001 u) at u ~ N(2185.5, 0.1^2): the lattice node h = 31.17 floor(u) ~ 6.9e4
  // is a mixture whose neighbours weigh Phi(-5) = 2.9e-7 each, so Var h = 5.6e-4. E[h^2] - E[h]^2 in
  // float cancels to an error of ~300 (h^2 ~ 4.7e9), and the next rule's e^{-var/2} then wipes the
  // sine out; sum w (h - mean)^2 does not. Reference: the exact mixture, in double.
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::sin(dsl::floor(u) * 31.17 + u * 0.001); });
  for (double mu : {2184.5, 2186.5, 2187.5}) {  // where the old form failed (49 of 139 such cells)
    const double s = 0.1;
    double want = 0;
    for (int o = -1; o <= 1; ++o) {
      const double K = std::floor(mu) + o;
      const double p = 0.5 * (std::erfc(-(K + 1 - mu) / (s * std::sqrt(2.0))) -
                              std::erfc(-(K - mu) / (s * std::sqrt(2.0))));
      want += p * std::sin(31.17 * K + 0.001 * mu);
    }
    ASSERT_GT(std::fabs(want), 0.3) << "mu " << mu;  // the setup: a sine that can be wiped out
    // Float: the argument ~6.9e4 carries an ulp of 0.008.
    EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, 0.02)
        << "mu " << mu;
  }
}

TEST(Rules, AWideFootprintTakesTheLatticeAverage) {
  // h(floor(u)) with a footprint of many cells: the mixture covers K - 1..K + 1 and the cells beyond
  // take h's mean and variance over the lattice (sampled on the plain graph at compile time), so the
  // value tends to the pattern's average; renormalising three cells gives their average instead,
  // a different ~random value per pixel (noise in the far field). Reference: the exact sum over
  // cells, in double.
  const auto h = [](double i) { return fract(std::sin(i * 1.7 + 0.3) * 13.37); };
  const ir::Graph g =
      one_input([](dsl::Var u) { return dsl::fract(dsl::sin(dsl::floor(u) * 1.7 + 0.3) * 13.37); });
  for (double mu : {3.5, 10.2, -7.7, 100.3, 41.9})
    for (double s : {100.0, 300.0}) {  // the truth over ~240+ cells: within ~0.02 of the average
      double want = 0;
      for (double K = std::floor(mu - 8 * s); K <= mu + 8 * s; ++K)
        want += (0.5 * std::erfc(-(K + 1 - mu) / (s * std::sqrt(2.0))) -
                 0.5 * std::erfc(-(K - mu) / (s * std::sqrt(2.0)))) *
                h(K);
      EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, 0.04)
          << "mu " << mu << " s " << s;
    }
}

TEST(Rules, SurfaceCoordinatesAreCorrelatedByTheirScreenGradients) {
  // u and v with parallel screen gradients are one variable: u - v = mu - mv exactly, so
  // step(u - v + 0.3 s) is 1 (independence would give Phi(0.3 / sqrt 2) = 0.58); orthogonal
  // gradients keep them independent.
  ir::Graph g;
  {
    dsl::Tracer t(g);
    const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
    g.add_output("r", dsl::step(u - v + 0.003).id());
  }
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  auto run = [&](float gvx, float gvy) {
    return testing::run_one_pixel(p, {0.5f, 0.5f}, {0.01f, 0.01f}, {0.02f, gvx}, {0, gvy});
  };
  EXPECT_NEAR(run(0.02f, 0), 1.0, 1e-4);
  EXPECT_NEAR(run(0, 0.02f), 0.5 * std::erfc(-0.3 / std::sqrt(2.0) / std::sqrt(2.0)), 1e-4);
}

TEST(Rules, ACellBlendThatHidesItsJumpsTakesTheCellOfTheMean) {
  // 1D value noise: mix(h(i), h(i + 1), smoothstep(fract(u))), i = floor(u), is continuous where i
  // jumps (cell_continuous finds that on the plain graph): narrow footprints near a cell edge then
  // see one cell's blend, with fract's dominant side, instead of independent averages of the hash
  // and of the weight (which differ from the truth by ~0.1 here).
  const auto h = [](double i) { return fract(std::sin(i * 1.7 + 0.3) * 13.37); };
  const auto noise = [&](double x) {
    const double i = std::floor(x), f = x - i, w = f * f * (3 - 2 * f);
    return h(i) + (h(i + 1) - h(i)) * w;
  };
  const ir::Graph g = one_input([](dsl::Var u) {
    auto hash = [](dsl::Var i) { return dsl::fract(dsl::sin(i * 1.7 + 0.3) * 13.37); };
    const dsl::Var i = dsl::floor(u);
    return dsl::mix(hash(i), hash(i + 1.0), dsl::smoothstep(dsl::fract(u)));
  });
  for (double mu : {2.97, 2.995, 3.0, 3.005, 3.03, 3.5})
    for (double s : {0.005, 0.02, 0.05}) {
      const double want = expect(noise, mu, s);
      EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, 0.01)
          << "mu " << mu << " s " << s;
    }
  // A cheaper rule (box) on the lattice nodes takes the mean's cell alone and the lattice average for
  // the rest of the mass: as exact inside a cell, and the pattern's average for a wide footprint
  // (the exact sum over ~1200 cells is within 0.02 of it).
  for (double mu : {3.3, 3.5, 3.7})
    EXPECT_NEAR(run1(g, "box", static_cast<float>(mu), 0.01f), expect(noise, mu, 0.01), 0.01) << "mu " << mu;
  for (double mu : {3.5, -40.2}) {
    const double s = 300;
    double want = 0;
    for (double K = std::floor(mu - 8 * s); K <= mu + 8 * s; ++K)
      want += (0.5 * std::erfc(-(K + 1 - mu) / (s * std::sqrt(2.0))) -
               0.5 * std::erfc(-(K - mu) / (s * std::sqrt(2.0)))) *
              0.5 * (h(K) + h(K + 1));  // the blend's average over a cell: (h(K) + h(K + 1)) / 2
    EXPECT_NEAR(run1(g, "box", static_cast<float>(mu), static_cast<float>(s)), want, 0.04) << "mu " << mu;
  }
  // A floor whose jump shows (checkerboard's floor(u + 0.5) - floor(u)) keeps the Gaussian rules:
  // the expectation of the jump, 1/2 at it.
  const ir::Graph c = one_input([](dsl::Var u) { return dsl::floor(u + 0.5) - dsl::floor(u); });
  EXPECT_NEAR(run1(c, "gaussian", 3.0f, 0.02f), 0.5, 1e-4);
}

// Every rule tends to the plain shader as the footprint goes to 0: at 64 fixed points of each suite
// shader, the output error against the plain value at sd = eps. Away from jumps a smoothing rule's
// error is O(eps^2) (Gaussian, box, tent, Dorn, antithetic MC: symmetric kernels); a point within a
// few eps of a jump may differ by O(1), and the number of such points shrinks like eps. So: the
// count of points off by > 1e-3 must fall to at most 1 of 64 at eps = 1e-5 (more would mean a rule
// that does not converge), and the median error must fall >= 50x from eps = 1e-2
// to 1e-3 (rate ~2; >= 10x = rate 1 for Dorn, whose sd heuristic is not a kernel's).
TEST(Rules, EveryRuleConvergesToThePlainShader) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(-3, 3);
  std::vector<float> mu(64), mv(64);
  for (int i = 0; i < 64; ++i) mu[i] = U(rng), mv[i] = U(rng);
  for (const char* shader :
       {"checkerboard", "circles", "zigzag", "quadratic_sine", "fire", "bricks", "value_noise", "truchet"}) {
    shaders::Effects fx;
    const ir::Graph g = shaders::trace(shaders::find_shader(shader), fx);
    auto eval = [&](const std::string& rule, float eps) {
      const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
      std::vector<std::vector<float>> m(p.input_count, std::vector<float>(64, 0.0f)), s = m, gx = m, gy = m;
      for (int j = 0; j < p.input_count; ++j)
        for (int i = 0; i < 64; ++i) {
          const std::string& nm = p.input_names[j];
          m[j][i] = nm == "u" ? mu[i] : nm == "v" ? mv[i] : 0.0f;
          s[j][i] = (nm == "u" || nm == "v") ? eps : 0.0f;
          gx[j][i] = nm == "u" ? eps / 0.5f : 0.0f;
          gy[j][i] = nm == "v" ? eps / 0.5f : 0.0f;
        }
      compiler::Batch b;
      b.count = 64;
      for (int j = 0; j < p.input_count; ++j) {
        b.mean.push_back(m[j].data());
        b.sd.push_back(s[j].data());
        b.grad_x.push_back(gx[j].data());
        b.grad_y.push_back(gy[j].data());
      }
      std::vector<std::vector<float>> out(p.outputs.size(), std::vector<float>(64));
      std::vector<float*> ptr;
      for (auto& o : out) ptr.push_back(o.data());
      compiler::Evaluator(p).run(b, ptr);
      return out;
    };
    const auto plain = eval("none", 0);
    for (const char* rule :
         {"gaussian", "gaussian:rho=cov", "dorn", "box", "tent", "mc8", "rule1:box", "rule3"}) {
      auto errors = [&](float eps) {
        const auto o = eval(rule, eps);
        std::vector<double> e;
        for (std::size_t c = 0; c < o.size(); ++c)
          for (int i = 0; i < 64; ++i) e.push_back(std::fabs(o[c][i] - plain[c][i]));
        return e;
      };
      const auto e5 = errors(1e-5f);
      int off = 0;  // points (any channel) off by more than 1e-3
      for (int i = 0; i < 64; ++i) {
        bool bad = false;
        for (std::size_t c = 0; c < e5.size() / 64; ++c) bad = bad || !(e5[c * 64 + i] <= 1e-3);
        off += bad;
      }
      EXPECT_LE(off, 1) << shader << " " << rule << " does not converge to the plain shader";
      auto median = [](std::vector<double> e) {
        std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
        return e[e.size() / 2];
      };
      const double m2 = median(errors(1e-2f)), m3 = median(errors(1e-3f));
      if (m2 > 1e-5)  // below that, float rounding of the plain value dominates
        EXPECT_GE(m2 / std::max(m3, 1e-9), std::string(rule) == "dorn" ? 10.0 : 50.0)
            << shader << " " << rule << " median error " << m2 << " -> " << m3;
    }
  }
}

// The singular slope the bumps scenes' cap rims have: sqrt(saturate(x)) at x = 0. Its Gaussian
// smoothing converges at rate 1/2 only (E = c sqrt(s)), which is the floor issue 13 measured there;
// this names it so a change of rate is noticed.
TEST(Rules, SqrtAtZeroConvergesAtRateOneHalf) {
  const ir::Graph g = one_input([](dsl::Var u) { return dsl::sqrt(dsl::saturate(u)); });
  for (const char* rule : {"gaussian", "tent"}) {
    const double e2 = run1(g, rule, 0.0f, 1e-2f), e4 = run1(g, rule, 0.0f, 1e-4f);
    EXPECT_NEAR(std::log10(e2 / e4) / 2, 0.5, 0.05) << rule << " " << e2 << " " << e4;
  }
}

double square_wave(double x) {
  return fract(x) < 0.5 ? 1.0 : 0.0;
}

// The intervals of square(t) * square(n t + d) = 1 against dense sampling of the product.
TEST(Rules, SquareProductIntervalsMatchSampling) {
  for (int n : {1, 2, 3, 4, -4, 7}) {
    for (double d : {0.0, 0.3, -1.7, 0.25}) {
      const auto pieces = compiler::square_product_intervals(n, d);
      for (int i = 0; i < 10000; ++i) {
        const double t = (i + 0.37) / 10000;
        bool in = false;
        for (const auto& [a, b] : pieces) in = in || (t >= a && t < b);
        EXPECT_EQ(in, square_wave(t) * square_wave(n * t + d) == 1.0)
            << "n " << n << " d " << d << " t " << t;
      }
    }
  }
}

// Zigzag's colour: band = square(2y), hue = square(y / 2), mix(mix(.., hue), mix(.., hue), band), a
// product of two square waves of one root. The lowering's exact form against quadrature: at and next
// to the jumps they share (every 4th band edge), narrow and wide kernels, large |mean|.
TEST(Rules, ProductOfTwoSquareWavesOfOneRootIsExact) {
  const ir::Graph g = one_input([](dsl::Var y) {
    dsl::Var band = dsl::square(y * 2.0), hue = dsl::square(y * 0.5);
    dsl::Var a = dsl::mix(dsl::Var(0.95), dsl::Var(0.2), hue),
             b = dsl::mix(dsl::Var(0.6), dsl::Var(0.1), hue);
    return dsl::mix(b, a, band);
  });
  const auto truth = [](double y) {
    const double band = square_wave(2 * y), hue = square_wave(0.5 * y);
    const double a = 0.95 + (0.2 - 0.95) * hue, b = 0.6 + (0.1 - 0.6) * hue;
    return b + (a - b) * band;
  };
  for (double mu : {0.0, 0.01, -0.02, 1.0, 0.25, 0.5, 0.37, 2.0, 37.0})
    for (double s : {0.003, 0.03, 0.1, 0.3, 3.0}) {
      const double want = expect(truth, mu, s);
      EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, 2e-4)
          << "mu " << mu << " s " << s;
    }
  // Before this rule (Stein covariance phi^2 for two jumps at one place, truth Phi (1 - Phi)) the
  // error at y = 0, s = 0.03 was ~0.1 of the colour step: checked above within 2e-4.
}

// abs(sin(x)) (fire's octaves) against quadrature: the composed rule (abs of a Gaussian with sin's
// moments) tends to 0.564 for wide kernels where the truth is 2/pi = 0.637; the Fourier form is exact
// there and the composed rule is kept for s < 0.15.
TEST(Rules, AbsOfSinMatchesQuadrature) {
  const ir::Graph g = one_input([](dsl::Var x) { return dsl::abs(dsl::sin(x)); });
  const auto truth = [](double x) { return std::fabs(std::sin(x)); };
  for (double mu : {0.0, 0.3, 1.5707963, 3.1415926, 2.0, 40.0, 1000.0})
    for (double s : {0.001, 0.05, 0.1, 0.149, 0.151, 0.3, 1.0, 5.0, 300.0}) {
      const double want = expect(truth, mu, s), tol = s < 0.15 ? 1.5e-3 : 3e-4;
      EXPECT_NEAR(run1(g, "gaussian", static_cast<float>(mu), static_cast<float>(s)), want, tol)
          << "mu " << mu << " s " << s;
    }
}

}  // namespace
}  // namespace bl
