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
#include "compiler/graph_facts.hpp"
#include "compiler/lower.hpp"
#include "dsl/math.hpp"
#include "shaders/effects.hpp"
#include "tests/runtime/one_pixel.hpp"
#include "tests/runtime/quadrature.hpp"

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

// E[f(U, V)], U ~ N(mu, s^2), V ~ N(mv, s^2); f is shade by default.
double expect2(double mu, double mv, double s, int n = 400, double (*f)(double, double) = shade<double>) {
  return testing::gaussian_mean_2d(f, mu, mv, s, s, n);
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

TEST(BernoulliMixture, ACascadeMixesOverItsWinner) {
  // `x = 0; if (u < tu) x = 0.5; if (v < tv) x = -1; if (w < tw) x = 1;` then exp(2x): the last
  // condition that holds picks x, so with independent u, v, w the mean is exactly
  // pw e^2 + (1 - pw)(pv e^-2 + (1 - pv)(pu e^1 + (1 - pu) e^0)). Three links are more than the
  // kMaxJoint comparisons mixed jointly; the third one's select averaged its branches before exp.
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true),
                 w = dsl::Var::input("w", true);
  const double tu = 0.3, tv = -0.2, tw = 0.6;
  dsl::Var x = dsl::select(dsl::less(u, dsl::Var(tu)), dsl::Var(0.5), dsl::Var(0.0));
  x = dsl::select(dsl::less(v, dsl::Var(tv)), dsl::Var(-1.0), x);
  x = dsl::select(dsl::less(w, dsl::Var(tw)), dsl::Var(1.0), x);
  g.add_output("r", dsl::exp(x * 2.0).id());
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  for (double m : {0.0, 0.3, -0.2, 0.6, 2.0})
    for (double s : {1e-4, 0.1, 0.5, 3.0}) {
      const double pu = Phi((tu - m) / s), pv = Phi((tv - m) / s), pw = Phi((tw - m) / s);
      const double want =
          pw * std::exp(2.0) + (1 - pw) * (pv * std::exp(-2.0) + (1 - pv) * (pu * std::exp(1.0) + (1 - pu)));
      const float mf = static_cast<float>(m), sf = static_cast<float>(s);
      // The uniform rule reads each input's sd; the gradients feed only rho modes it does not use.
      EXPECT_NEAR(testing::run_one_pixel(p, {mf, mf, mf}, {sf, sf, sf}, {sf, 0, 0}, {0, sf, 0}), want,
                  2e-5 * std::exp(2.0))
          << "m " << m << " s " << s;
    }
}

TEST(BernoulliMixture, TheHashOfTheCellACascadePicksIsAMixtureOfCells) {
  // id = floor(u); if (v < t1) id = floor(u) + 1; if (v < t2) id = floor(u) + 2; if (v < t3) id = floor(u) +
  // 3; then h(id), h a lattice hash: in each outcome of the cascade h(floor(u) + k) is a function of the cell
  // alone, so E = sum_k w_k sum_K P(floor(u) = K) h(K + k), exactly (u, v independent). Smoothing h of the
  // picked id's (mean, variance) instead gives ~ its average over the whole hash.
  const auto h = [](double i) {
    const double x = std::sin(i * 1.7 + 0.3) * 13.37;
    return x - std::floor(x);
  };
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
  const double th[3] = {0.5, 0.0, -0.4};
  const dsl::Var cell = dsl::floor(u);
  dsl::Var id = cell;
  for (int k = 0; k < 3; ++k) id = dsl::select(dsl::less(v, dsl::Var(th[k])), cell + double(k + 1), id);
  g.add_output("r", dsl::fract(dsl::sin(id * 1.7 + 0.3) * 13.37).id());
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  for (double mu : {3.5, 3.2, -6.7})
    for (double mv : {0.0, 0.5, -0.3})
      for (double s : {0.01, 0.1, 0.3}) {
        double want = 0, above = 1;  // above: P(no link above holds)
        for (int k = 3; k >= 0; --k) {
          const double pk = k > 0 ? Phi((th[k - 1] - mv) / s) : 1.0, w = above * pk;
          above *= 1 - pk;
          for (int o = -2; o <= 2; ++o) {
            const double K = std::floor(mu) + o, pK = Phi((K + 1 - mu) / s) - Phi((K - mu) / s);
            want += w * pK * h(K + k);
          }
        }
        const float m = static_cast<float>(mu), n = static_cast<float>(mv), sf = static_cast<float>(s);
        EXPECT_NEAR(testing::run_one_pixel(p, {m, n}, {sf, sf}, {sf / 0.5f, 0}, {0, sf / 0.5f}), want, 2e-3)
            << "mu " << mu << " mv " << mv << " s " << s;
      }
}

// A cellular (Voronoi) border as users write it: the nearest and second-nearest of four feature points
// by `if (d < best) { second = best; best = d; } else if (d < second) second = d;`, dark where
// sqrt(second) - sqrt(best) is below 0.12.
constexpr double kSites[4][2] = {{0.0, 0.0}, {1.0, 0.1}, {0.2, 1.1}, {1.1, 0.9}};

double border(double u, double v) {
  double best = 8, second = 8;
  for (const auto& c : kSites) {
    const double d = (u - c[0]) * (u - c[0]) + (v - c[1]) * (v - c[1]);
    if (d < best) {
      second = best;
      best = d;
    } else if (d < second) {
      second = d;
    }
  }
  const double t = std::clamp((std::sqrt(second) - std::sqrt(best)) / 0.12, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// flipped: the same search written `if (best <= d) { ... } else { nearer }`, the running value on the
// comparison's left.
ir::Graph border_graph(bool flipped = false) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
  dsl::Var best(8.0), second(8.0);
  for (const auto& c : kSites) {
    const dsl::Var d = (u - c[0]) * (u - c[0]) + (v - c[1]) * (v - c[1]);
    const dsl::Var farther = dsl::less(best, d);
    if (flipped) {
      second = dsl::select(farther, dsl::select(dsl::less(d, second), d, second), best);
      best = dsl::select(farther, best, d);
      continue;
    }
    const dsl::Var nearer = dsl::less(d, best);
    second = dsl::select(nearer, best, dsl::select(dsl::less(d, second), d, second));
    best = dsl::select(nearer, d, best);
  }
  g.add_output("r", dsl::smoothstep(dsl::Var(0.0), dsl::Var(0.12), dsl::sqrt(second) - dsl::sqrt(best)).id());
  return g;
}

TEST(BernoulliMixture, ACascadesWinnerIsNearerThanTheOthers) {
  // The branch where site j is the nearest conditions d_j < best (both random) and the later sites'
  // d_l >= d_j; without it the branch kept the footprint where j loses, where the border term is
  // negative, and borders came out too dark (Voronoi all-Gaussian 0.0516 -> 0.0343).
  const ir::Graph g = border_graph(), flipped = border_graph(true);
  double sq = 0;
  int n = 0;
  for (const auto& [mu, mv] : {std::pair{0.5, 0.3}, std::pair{0.45, 0.5}, std::pair{0.6, 0.55},
                               std::pair{0.2, 0.2}, std::pair{0.55, 0.05}})
    for (double s : {1e-4, 0.01, 0.03, 0.06, 0.1}) {
      const double want = expect2(mu, mv, s, 300, border);
      const double got =
          run(g, "gaussian", static_cast<float>(mu), static_cast<float>(mv), static_cast<float>(s));
      EXPECT_NEAR(got, want, 0.2) << "mu " << mu << ", " << mv << " s " << s;  // without: up to 0.36 off
      const double got_flipped =
          run(flipped, "gaussian", static_cast<float>(mu), static_cast<float>(mv), static_cast<float>(s));
      // The same search written the other way round gives the same value (taking the running value
      // for the candidate instead: up to 0.12 apart).
      EXPECT_NEAR(got_flipped, got, 1e-4) << "flipped, mu " << mu << ", " << mv << " s " << s;
      sq += (got - want) * (got - want);
      ++n;
    }
  // Over these 25 footprints: 0.064 (without the conditioning 0.14, every miss too dark).
  EXPECT_LT(std::sqrt(sq / n), 0.1);
  // A footprint three site spacings wide: finite and inside [0, 1] (it was NaN: the first link,
  // d < 8, truncated d's Gaussian below 0 and sqrt's kernel took it). Not accurate: the borders fade
  // out (1.0 where the area average is 0.44); a cellular pattern needs its far-field average there.
  for (const auto& [mu, mv] : {std::pair{0.5, 0.3}, std::pair{0.2, 0.2}}) {
    const float got = run(g, "gaussian", static_cast<float>(mu), static_cast<float>(mv), 3.0f);
    EXPECT_TRUE(got >= 0 && got <= 1) << got;
  }
}

TEST(BernoulliMixture, TheProcessMemoOfLatticeFactsStaysBounded) {
  // Lowering memoises the lattice facts of each graph for the process; shader after shader (an
  // embedding) must not grow that memo without end, and a cleared memo must give the same program.
  auto graph = [](double gain) {
    ir::Graph g;
    dsl::Tracer t(g);
    const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
    const dsl::Var cell = dsl::floor(u);
    const dsl::Var id = dsl::select(dsl::less(v, dsl::Var(0.25)), cell + 1.0, cell);
    g.add_output("r", dsl::fract(dsl::sin(id * 1.7 + 0.3) * gain).id());
    return g;
  };
  const std::size_t saved = compiler::process_memo_limit();
  compiler::process_memo_limit() = 6;
  auto value = [&](double gain) {
    const ir::Graph g = graph(gain);
    const compiler::Program p =
        compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
    return testing::run_one_pixel(p, {3.3f, 0.2f}, {0.2f, 0.2f}, {0.4f, 0}, {0, 0.4f});
  };
  const float first = value(13.37);
  for (int k = 0; k < 20; ++k) {
    value(13.37 + k);
    EXPECT_LE(compiler::GraphFacts::process_memo_entries(), 2 * compiler::process_memo_limit())
        << "graph " << k;
  }
  EXPECT_EQ(value(13.37), first);  // its memo entries long cleared
  compiler::process_memo_limit() = saved;
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
