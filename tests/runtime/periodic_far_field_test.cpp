// Tilings (outputs that see u, v only through fract / mod of affine coordinates): which outputs are
// found, their spatial moments against closed forms, the all-Gaussian value at wide footprints and
// at a hexagonal tiling's mod seams against 2D quadrature.
#include "compiler/periodic_far_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "compiler/lower.hpp"
#include "dsl/math.hpp"
#include "rules/rule.hpp"
#include "tests/runtime/one_pixel.hpp"
#include "tests/runtime/quadrature.hpp"

namespace bl {
namespace {

using dsl::Var;

ir::Graph two_inputs(const std::function<Var(Var, Var)>& f) {
  ir::Graph g;
  dsl::Tracer t(g);
  const Var u = Var::input("u", true), v = Var::input("v", true);
  g.add_output("r", f(u, v).id());
  return g;
}

double run(const ir::Graph& g, double mu, double mv, double su, double sv) {
  const compiler::Program p =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  const float fu = static_cast<float>(su), fv = static_cast<float>(sv);
  return testing::run_one_pixel(p, {static_cast<float>(mu), static_cast<float>(mv)}, {fu, fv}, {fu / 0.5f, 0},
                                {0, fv / 0.5f});
}

double run(const ir::Graph& g, double mu, double mv, double s) {
  return run(g, mu, mv, s, s);
}

double expect2(const std::function<double(double, double)>& f, double mu, double mv, double su, double sv,
               int n = 400) {
  return testing::gaussian_mean_2d(f, mu, mv, su, sv, n);
}
double expect2(const std::function<double(double, double)>& f, double mu, double mv, double s, int n = 400) {
  return expect2(f, mu, mv, s, s, n);
}

double fract(double x) {
  return x - std::floor(x);
}
double smooth(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Dark discs on a grid of period 1/2: smoothstep(0.25, 0.3, |fract(2 uv) - 1/2|).
double discs(double u, double v) {
  return smooth(0.25, 0.3, std::hypot(fract(2 * u) - 0.5, fract(2 * v) - 0.5));
}
// The discs' area average: an n^2 midpoint rule over one period.
double discs_area_average(int n) {
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += discs((i + 0.5) / n * 0.5, (j + 0.5) / n * 0.5);
  return sum / (double(n) * n);
}
ir::Graph discs_graph() {
  return two_inputs([](Var u, Var v) {
    const Var x = dsl::fract(u * 2.0) - 0.5, y = dsl::fract(v * 2.0) - 0.5;
    return dsl::smoothstep(Var(0.25), Var(0.3), dsl::sqrt(x * x + y * y));
  });
}

// Hexagonal tiles as shader authors write them: the nearer of two offset mod lattices, its hexagonal
// distance, grout where that is above 0.44.
constexpr double kH = 1.7320508;
double hex(double u, double v) {
  auto m = [](double x, double c) { return x - c * std::floor(x / c); };
  const double ax = m(3 * u, 1) - 0.5, ay = m(3 * v, kH) - kH / 2;
  const double bx = m(3 * u - 0.5, 1) - 0.5, by = m(3 * v - kH / 2, kH) - kH / 2;
  const bool a = ax * ax + ay * ay < bx * bx + by * by;
  const double gx = std::fabs(a ? ax : bx), gy = std::fabs(a ? ay : by);
  return smooth(0.42, 0.46, std::max(0.5 * gx + 0.8660254 * gy, gx));
}
ir::Graph hex_graph() {
  return two_inputs([](Var u, Var v) {
    const Var ax = dsl::mod(u * 3.0, 1.0) - 0.5, ay = dsl::mod(v * 3.0, kH) - kH / 2;
    const Var bx = dsl::mod(u * 3.0 - 0.5, 1.0) - 0.5, by = dsl::mod(v * 3.0 - kH / 2, kH) - kH / 2;
    const Var a = dsl::less(ax * ax + ay * ay, bx * bx + by * by);
    const Var gx = dsl::abs(dsl::select(a, ax, bx)), gy = dsl::abs(dsl::select(a, ay, by));
    return dsl::smoothstep(Var(0.42), Var(0.46), dsl::max(gx * 0.5 + gy * 0.8660254, gx));
  });
}

TEST(PeriodicFarField, FindsTheOutputsThatSeeTheSurfaceOnlyThroughTiles) {
  ir::Graph g;
  dsl::Tracer t(g);
  const Var u = Var::input("u", true), v = Var::input("v", true), time = Var::input("time", false);
  const Var tile = dsl::fract(u * 3.0 + v) * dsl::mod(v - 0.2, 0.5);
  g.add_output("tile", tile.id());
  g.add_output("plus_u", (tile + u).id());                       // reads u directly
  g.add_output("cells", dsl::fract(dsl::floor(u) * 0.37).id());  // a floor is a lattice
  g.add_output("animated", dsl::fract(u * 2.0 + time).id());     // another input
  g.add_output("warped", dsl::fract(dsl::sin(u) * 3.0).id());    // not affine in u
  const compiler::PeriodicFarField f(g);
  const std::vector<int>& out = g.outputs();
  EXPECT_TRUE(f.periodic_output(out[0]));
  EXPECT_EQ(f.sources(out[0]).size(), 2u);
  for (int k = 1; k < 5; ++k) EXPECT_FALSE(f.periodic_output(out[k])) << g.output_names()[k];
  const std::vector<int>& src = f.sources(out[0]);
  EXPECT_TRUE(std::any_of(src.begin(), src.end(), [&](int j) { return f.period(j) == 0.5; }));  // the mod's
  EXPECT_TRUE(std::any_of(src.begin(), src.end(), [&](int j) { return f.period(j) == 1.0; }));  // fract's
}

TEST(PeriodicFarField, SpatialMomentsMatchClosedForms) {
  struct Case {
    ir::Graph g;
    double mean, second;
  };
  const Case cases[] = {
      {two_inputs([](Var u, Var) { return dsl::fract(u) * dsl::fract(u); }), 1.0 / 3, 1.0 / 5},
      {two_inputs([](Var, Var v) { return dsl::mod(v * 2.0 + 0.3, 0.5); }), 0.25, 1.0 / 12},
      {two_inputs([](Var u, Var v) { return dsl::fract(u * 7.0) * dsl::fract(v - u); }), 0.25, 1.0 / 9},
  };
  for (const Case& c : cases) {
    const compiler::PeriodicFarField f(c.g);
    const auto m = f.spatial(c.g.outputs()[0]);
    ASSERT_TRUE(m.ok);
    EXPECT_NEAR(m.mean, c.mean, 2e-3);
    EXPECT_NEAR(m.second, c.second, 2e-3);
  }
}

TEST(PeriodicFarField, WideFootprintsGiveTheTilingsAverage) {
  // The reference: the discs' area average by a 2000^2 midpoint rule over one period (at s = 1, two
  // periods, a Gaussian keeps exp(-8 pi^2) of the first harmonic).
  const double avg = discs_area_average(2000);
  const ir::Graph g = discs_graph();
  // Without the far field: 0.9986 where the average is 0.762 (the Gaussian stand-in for a uniform
  // fract puts the disc edge's distance beyond 0.3 nearly everywhere).
  for (const auto& [mu, mv] : {std::pair{0.1, 0.2}, std::pair{3.3, -1.7}, std::pair{40.25, 7.0}})
    EXPECT_NEAR(run(g, mu, mv, 1.0), avg, 3e-3) << mu << ", " << mv;
}

TEST(PeriodicFarField, HardInputsStayFiniteAndConverge) {
  const ir::Graph g = discs_graph();
  const double avg = discs_area_average(1000);
  // sigma -> 0: the plain pattern (inside a disc's rim, outside it, on the flat between).
  for (const auto& [mu, mv] : {std::pair{0.25, 0.25}, std::pair{0.1, 0.2}, std::pair{0.0, 0.0}})
    for (double s : {0.0, 1e-7})
      EXPECT_NEAR(run(g, mu, mv, s), discs(mu, mv), 1e-4) << mu << ", " << mv << " s " << s;
  // Huge footprints and huge |u|: the average (float inputs: |u| = 1e4 keeps 1e-3 of a period).
  for (double s : {10.0, 1e3, 1e6}) EXPECT_NEAR(run(g, 0.3, 0.1, s), avg, 3e-3) << s;
  EXPECT_NEAR(run(g, 1e4 + 0.1, -1e4, 2.0), avg, 3e-3);
  // Across the blend (0.3 to 0.5 periods: s = 0.15 to 0.25 here) and around it: finite, in [0, 1].
  for (double mu : {0.0, 0.13, 0.25, 7.7})
    for (double s = 0.01; s < 20; s *= 1.3) {
      const double y = run(g, mu, 0.4 * mu, s);
      EXPECT_TRUE(y >= 0 && y <= 1) << mu << " s " << s << ": " << y;
    }
}

TEST(PeriodicFarField, AStripePatternIsItsDampedFourierSeries) {
  // An output of u alone through fract (axis-aligned, v absent): from 0.045 periods on, the damped
  // series of the output itself, exact to its 12 terms (1D quadrature, 4000 points on +-8 s).
  const ir::Graph g =
      two_inputs([](Var u, Var) { return dsl::smoothstep(Var(0.2), Var(0.3), dsl::fract(u * 2.0)); });
  auto stripe = [](double u) { return smooth(0.2, 0.3, fract(2 * u)); };
  const compiler::PeriodicFarField f(g);
  const auto ax = f.axes(g.outputs()[0]);
  ASSERT_TRUE(ax.ok);
  EXPECT_EQ(ax.v.input, -1);
  EXPECT_DOUBLE_EQ(ax.u.period, 0.5);
  double worst = 0;
  for (double mu : {0.0, 0.11, 0.15, 0.26, 0.4, 13.37})
    for (double s : {0.025, 0.03, 0.06, 0.1, 0.2}) {
      const double want = testing::gaussian_mean_1d(stripe, mu, s, 4000), got = run(g, mu, 0.3, s, 0.01);
      EXPECT_NEAR(got, want, 2e-3) << mu << " s " << s;  // without: up to 0.21 off
      worst = std::max(worst, std::fabs(got - want));
    }
  std::printf("stripes: worst |series - quadrature| %.2g\n", worst);
}

TEST(PeriodicFarField, ABandCoveringOneAxisIsTheOtherAxissSeries) {
  // Discs under a footprint long along v (2 periods) and short along u (0.05-0.2 periods), as below a
  // horizon: the series in u of the pattern averaged over v, against 2D quadrature. The hexagonal
  // tiles' band was too dark by up to 0.3 (all-Gaussian 0.0558 -> 0.0344, MSAA-16 0.0342).
  const ir::Graph g = discs_graph();
  double worst = 0;
  for (const auto& [mu, mv] :
       {std::pair{0.1, 0.2}, std::pair{0.25, 0.25}, std::pair{0.3, 0.0}, std::pair{5.05, 2.2}})
    for (double su : {0.025, 0.05, 0.1}) {
      const double want = expect2(discs, mu, mv, su, 1.0), got = run(g, mu, mv, su, 1.0);
      EXPECT_NEAR(got, want, 3e-3) << mu << ", " << mv << " su " << su;  // without: up to 0.36 off
      worst = std::max(worst, std::fabs(got - want));
      // The same footprint turned: the series in v.
      const double want_t = expect2(discs, mv, mu, 1.0, su), got_t = run(g, mv, mu, 1.0, su);
      EXPECT_NEAR(got_t, want_t, 3e-3) << mv << ", " << mu << " sv " << su;
    }
  std::printf("discs band: worst |series - quadrature| %.2g\n", worst);
}

TEST(PeriodicFarField, AHexagonalTilingsModSeamsKeepTheSideTheFootprintHolds) {
  // Footprints on the seams of the mod lattices (3u or 3v - sqrt(3)/2 at a whole period) and inside
  // tiles, at 1-10% of a tile: all-Gaussian against 2D quadrature. mod's full rule averaged both
  // sides of a seam (mean 0, the grout's |.| too small) and drew lines across the tiles.
  const ir::Graph g = hex_graph();
  double sq = 0;
  int count = 0;
  for (const auto& [mu, mv] :
       {std::pair{1.0 / 3, 0.05}, std::pair{2.0 / 3 + 0.002, 0.6}, std::pair{0.5, kH / 6},
        std::pair{0.17, kH / 3 + 0.003}, std::pair{0.12, 0.1}, std::pair{0.4, 0.45}})
    for (double s : {0.003, 0.01, 0.03}) {
      const double want = expect2(hex, mu, mv, s, 300), got = run(g, mu, mv, s);
      // Without: up to 0.43 off (0.57 where the quadrature says 1.0, a tile's inside at a seam).
      EXPECT_NEAR(got, want, 0.2) << mu << ", " << mv << " s " << s;
      sq += (got - want) * (got - want);
      ++count;
    }
  // Over these 18 footprints 0.057 (without: 0.167); what is left is at 10% of a tile, off the seams,
  // the Gaussian rule's own error on max and smoothstep (0.16 at (0.12, 0.1), as before).
  EXPECT_LT(std::sqrt(sq / count), 0.08);
}

}  // namespace
}  // namespace bl
