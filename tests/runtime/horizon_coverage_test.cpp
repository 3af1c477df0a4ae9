// The pixel filter's coverage of the ground plane at the horizon (camera/horizon_coverage.hpp)
// against Monte Carlo over the filter: point traces (trace_pixel) of N(c, s^2 I) samples.
#include "camera/horizon_coverage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera/plane_batch.hpp"

namespace {

using namespace bl::camera;

Camera tilted() {
  Camera cam;
  cam.position = {0.3, -0.2, 2.0};
  cam.yaw_deg = 20;
  cam.pitch_deg = -15;
  cam.roll_deg = 12;  // a slanted horizon: the normal is not an image axis
  cam.width = 64;
  cam.height = 48;
  return cam;
}

struct McResult {
  double fraction, px, py;
};

McResult monte_carlo(const Camera& cam, double s, double px, double py, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, s);
  const Basis b = basis(cam);
  long hits = 0;
  double sx = 0, sy = 0;
  for (int k = 0; k < n; ++k) {
    const double x = px + g(rng), y = py + g(rng);
    if (!trace_pixel(cam, b, FootprintOptions{}, x, y).hit) continue;
    ++hits, sx += x, sy += y;
  }
  return {double(hits) / n, hits ? sx / hits : px, hits ? sy / hits : py};
}

// Pixels in a column across the horizon: fraction and the covered part's mean image point agree with
// Monte Carlo within 4.5 standard errors, for two filter widths.
TEST(HorizonCoverage, MatchesMonteCarloAcrossTheHorizon) {
  const Camera cam = tilted();
  const Basis b = basis(cam);
  int straddling = 0;
  for (double s : {0.5, 1.3}) {
    for (int y = 0; y < cam.height; ++y) {
      const double px = 40.5, py = y + 0.5;
      const Coverage c = horizon_coverage(cam, b, s, px, py);
      if (c.fraction < 1e-3 || c.fraction > 1 - 1e-3) continue;
      ++straddling;
      const int n = 200000;
      const McResult mc = monte_carlo(cam, s, px, py, n, 17 + y);
      const double se = std::sqrt(c.fraction * (1 - c.fraction) / n);
      EXPECT_NEAR(c.fraction, mc.fraction, 4.5 * se + 1e-9) << "s " << s << " row " << y;
      // The mean of about fraction * n samples of spread at most s.
      const double se_mean = s / std::sqrt(c.fraction * n);
      EXPECT_NEAR(c.px, mc.px, 4.5 * se_mean) << "s " << s << " row " << y;
      EXPECT_NEAR(c.py, mc.py, 4.5 * se_mean) << "s " << s << " row " << y;
      // The covered part's mean lies on the plane.
      EXPECT_TRUE(trace_pixel(cam, b, FootprintOptions{}, c.px, c.py).hit);
    }
  }
  EXPECT_GE(straddling, 4);
}

// Far below the horizon the footprint trace is the centre's point trace with coverage 1; far above,
// a miss; with no horizon in the image (looking straight down) or s = 0, the centre's hit decides.
TEST(HorizonCoverage, AwayFromTheHorizonItIsThePointTrace) {
  const Camera cam = tilted();
  const Basis b = basis(cam);
  FootprintOptions opt;
  const PlaneSample below = trace_footprint(cam, b, opt, 10.5, 47.5),
                    point = trace_pixel(cam, b, opt, 10.5, 47.5);
  ASSERT_TRUE(point.hit);
  EXPECT_TRUE(below.hit);
  EXPECT_EQ(below.coverage, 1.0);
  EXPECT_EQ(below.u, point.u);
  EXPECT_EQ(below.sigma_v, point.sigma_v);
  EXPECT_FALSE(trace_footprint(cam, b, opt, 10.5, 0.5).hit);
  EXPECT_EQ(trace_footprint(cam, b, opt, 10.5, 0.5).coverage, 0.0);

  Camera down;
  down.position = {0, 0, 3};
  down.pitch_deg = -90;
  down.width = down.height = 16;
  EXPECT_EQ(horizon_coverage(down, basis(down), 0.5, 0.5, 0.5).fraction, 1.0);
  // s = 0: a step at the horizon line.
  int ones = 0, zeros = 0;
  for (int y = 0; y < cam.height; ++y) {
    const double f = horizon_coverage(cam, b, 0.0, 40.5, y + 0.5).fraction;
    EXPECT_TRUE(f == 0.0 || f == 1.0);
    EXPECT_EQ(f == 1.0, trace_pixel(cam, b, opt, 40.5, y + 0.5).hit);
    (f == 1.0 ? ones : zeros)++;
  }
  EXPECT_GT(ones, 0);
  EXPECT_GT(zeros, 0);
}

// The batch trace with horizon_coverage: pixels whose centre misses but whose filter reaches the
// plane become hits with coverage < 1/2; jittered (offset) traces keep point semantics.
TEST(HorizonCoverage, BatchTraceCarriesCoverage) {
  const Camera cam = tilted();
  FootprintOptions opt;
  opt.horizon_coverage = true;
  PlaneBatch with, without;
  trace_plane(cam, opt, with);
  trace_plane(cam, FootprintOptions{}, without);
  int gained = 0, partial = 0;
  for (std::size_t i = 0; i < with.size(); ++i) {
    const double x = i % cam.width + 0.5, y = i / cam.width + 0.5;
    const Coverage c = horizon_coverage(cam, basis(cam), opt.pixel_sigma, x, y);
    const double want = c.fraction < kMinCoverage ? 0.0 : c.fraction > 1 - kMinCoverage ? 1.0 : c.fraction;
    EXPECT_NEAR(with.coverage[i], want, 1e-6) << i;
    EXPECT_EQ(bool(with.hit[i]), with.coverage[i] > 0) << i;
    EXPECT_EQ(without.coverage[i], without.hit[i] ? 1.0f : 0.0f) << i;
    if (with.hit[i] && !without.hit[i]) {
      ++gained;
      EXPECT_LT(with.coverage[i], 0.5f);
    }
    partial += with.coverage[i] > 0 && with.coverage[i] < 1;
  }
  EXPECT_GT(gained, 0);
  EXPECT_GT(partial, gained);
  std::vector<float> zero(2 * with.size(), 0.0f);
  PlaneBatch jittered;
  trace_plane(cam, opt, jittered, {}, zero.data());
  for (std::size_t i = 0; i < jittered.size(); ++i) EXPECT_EQ(jittered.hit[i], without.hit[i]) << i;
}

}  // namespace
