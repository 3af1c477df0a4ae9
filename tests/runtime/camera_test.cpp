// Ground-plane camera: hit points, differentials and footprints against hand geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "camera/plane_batch.hpp"
#include "camera/plane_hit.hpp"

namespace {

using namespace bl::camera;
constexpr double kPi = 3.14159265358979323846;
double rad(double deg) {
  return deg * kPi / 180.0;
}

Camera straight_down(double h, double fov, int w, int hgt) {
  Camera cam;
  cam.position = {2.0, -1.0, h};
  cam.yaw_deg = 90;  // image right = +x, image up = +y
  cam.pitch_deg = -90;
  cam.vfov_deg = fov;
  cam.width = w;
  cam.height = hgt;
  return cam;
}

// Looking straight down, one pixel spans 2 h tan(fov/2) / height world units everywhere.
TEST(RuntimeCamera, StraightDownHasConstantPixelFootprint) {
  const double h = 3.0, fov = 50.0, k = 3.0;
  const Camera cam = straight_down(h, fov, 80, 60);
  const double pixel = k * 2.0 * h * std::tan(rad(fov) / 2) / 60;
  for (FootprintBound bound : {FootprintBound::kDornAxisAligned, FootprintBound::kGaussianMarginal}) {
    FootprintOptions opt;
    opt.texture_scale = k;
    opt.bound = bound;
    for (int j = 0; j < 60; j += 7) {
      for (int i = 0; i < 80; i += 9) {
        const PlaneSample s = trace_pixel(cam, opt, i + 0.5, j + 0.5);
        ASSERT_TRUE(s.hit);
        EXPECT_NEAR(s.du_dx, pixel, 1e-12);
        EXPECT_NEAR(s.dv_dy, -pixel, 1e-12);  // image y is down, world y is up the image
        EXPECT_NEAR(s.du_dy, 0.0, 1e-12);
        EXPECT_NEAR(s.dv_dx, 0.0, 1e-12);
        EXPECT_NEAR(s.sigma_u, 0.5 * pixel, 1e-12);
        EXPECT_NEAR(s.sigma_v, 0.5 * pixel, 1e-12);
        EXPECT_NEAR(s.rho, 0.0, 1e-12);
        // Hit point by hand: centre of the image is below the camera.
        EXPECT_NEAR(s.u, k * 2.0 + (i + 0.5 - 40) * pixel, 1e-10);
        EXPECT_NEAR(s.v, k * -1.0 - (j + 0.5 - 30) * pixel, 1e-10);
      }
    }
  }
  const PlaneSample c = trace_pixel(cam, FootprintOptions{}, 40.0, 30.0);
  EXPECT_NEAR(c.distance, h, 1e-12);
  EXPECT_NEAR(c.view_z, 1.0, 1e-12);
}

TEST(RuntimeCamera, OrientationConventions) {
  Camera cam;
  cam.position = {0, 0, 2};
  cam.pitch_deg = -45;
  cam.width = cam.height = 10;
  // yaw 0 looks along +x, yaw 90 along +y: a 45-degree ray from height 2 lands 2 units away.
  PlaneSample s = trace_pixel(cam, FootprintOptions{}, 5.0, 5.0);
  EXPECT_NEAR(s.u, 2.0, 1e-12);
  EXPECT_NEAR(s.v, 0.0, 1e-12);
  cam.yaw_deg = 90;
  s = trace_pixel(cam, FootprintOptions{}, 5.0, 5.0);
  EXPECT_NEAR(s.u, 0.0, 1e-12);
  EXPECT_NEAR(s.v, 2.0, 1e-12);
  EXPECT_NEAR(s.distance, 2.0 * std::sqrt(2.0), 1e-12);
  // Straight down, yaw 90: roll 90 turns image right from +x to +y.
  // Camera over (2, -1) at height 1; 4 pixels right of centre is 4 / f = 4 tan(30 deg) / 5 away.
  Camera down = straight_down(1.0, 60, 10, 10);
  const double step = 4.0 * std::tan(rad(30.0)) / 5.0;
  PlaneSample right = trace_pixel(down, FootprintOptions{}, 9.0, 5.0);
  EXPECT_NEAR(right.u, 2.0 + step, 1e-12);
  EXPECT_NEAR(right.v, -1.0, 1e-12);
  down.roll_deg = 90;
  right = trace_pixel(down, FootprintOptions{}, 9.0, 5.0);
  EXPECT_NEAR(right.u, 2.0, 1e-12);
  EXPECT_NEAR(right.v, -1.0 + step, 1e-12);
}

// The analytic differentials against central differences of the hit point itself.
TEST(RuntimeCamera, DifferentialsMatchFiniteDifferences) {
  Camera cam;
  cam.position = {0.3, -0.7, 1.7};
  cam.yaw_deg = 37;
  cam.pitch_deg = -25;
  cam.roll_deg = 12;
  cam.vfov_deg = 70;
  cam.width = 96;
  cam.height = 64;
  FootprintOptions opt;
  opt.texture_scale = 4.0;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0, 96), uy(0, 64);
  int checked = 0;
  const double h = 1e-4;
  for (int n = 0; n < 400; ++n) {
    const double px = ux(rng), py = uy(rng);
    const PlaneSample s = trace_pixel(cam, opt, px, py);
    const PlaneSample xp = trace_pixel(cam, opt, px + h, py), xm = trace_pixel(cam, opt, px - h, py);
    const PlaneSample yp = trace_pixel(cam, opt, px, py + h), ym = trace_pixel(cam, opt, px, py - h);
    if (!(s.hit && xp.hit && xm.hit && yp.hit && ym.hit)) continue;
    ++checked;
    const double fd[4] = {(xp.u - xm.u) / (2 * h), (yp.u - ym.u) / (2 * h), (xp.v - xm.v) / (2 * h),
                          (yp.v - ym.v) / (2 * h)};
    const double an[4] = {s.du_dx, s.du_dy, s.dv_dx, s.dv_dy};
    const double scale = std::hypot(std::hypot(an[0], an[1]), std::hypot(an[2], an[3]));
    for (int c = 0; c < 4; ++c) EXPECT_LE(std::abs(fd[c] - an[c]), 1e-6 * scale) << "component " << c;
  }
  EXPECT_GT(checked, 100);  // the view sees the ground in a good part of the image
}

TEST(RuntimeCamera, PixelsAboveTheHorizonMiss) {
  Camera cam;
  cam.position = {0, 0, 1.5};
  cam.pitch_deg = 0;  // horizon exactly at py = height / 2
  cam.width = 8;
  cam.height = 20;
  for (int j = 0; j < 20; ++j) {
    const PlaneSample s = trace_pixel(cam, FootprintOptions{}, 3.5, j + 0.5);
    EXPECT_EQ(s.hit, j >= 10) << "row " << j;
    if (!s.hit) EXPECT_EQ(s.sigma_u, 0.0);
  }
  // Tilted 10 degrees down: the horizon is at py = H/2 - f tan(10 deg).
  cam.pitch_deg = -10;
  const double f = 10.0 / std::tan(rad(30.0));
  const double horizon = 10.0 - f * std::tan(rad(10.0));
  EXPECT_FALSE(trace_pixel(cam, FootprintOptions{}, 4.0, horizon - 1e-6).hit);
  const PlaneSample below = trace_pixel(cam, FootprintOptions{}, 4.0, horizon + 1e-3);
  EXPECT_TRUE(below.hit);
  EXPECT_GT(below.distance, 1000.0);
  FootprintOptions near_only;
  near_only.max_distance = 100.0;
  EXPECT_FALSE(trace_pixel(cam, near_only, 4.0, horizon + 1e-3).hit);
}

// At the image centre of a camera pitched down by theta, a pixel maps to D / f across and
// D / (f sin theta) along the view (foreshortening), D = h / sin theta.
TEST(RuntimeCamera, GrazingViewIsAnisotropicByOneOverSinTheta) {
  for (double theta : {10.0, 30.0}) {
    Camera cam;
    cam.position = {0, 0, 2.0};
    cam.yaw_deg = 90;  // looking along +y
    cam.pitch_deg = -theta;
    cam.vfov_deg = 40;
    cam.width = 64;
    cam.height = 48;
    FootprintOptions opt;
    opt.texture_scale = 2.0;
    const PlaneSample s = trace_pixel(cam, opt, 32.0, 24.0);
    ASSERT_TRUE(s.hit);
    const double f = 24.0 / std::tan(rad(20.0)), D = 2.0 / std::sin(rad(theta));
    EXPECT_NEAR(s.distance, D, 1e-12);
    EXPECT_NEAR(s.v, 2.0 * 2.0 / std::tan(rad(theta)), 1e-12);
    EXPECT_NEAR(s.sigma_u, 0.5 * 2.0 * D / f, 1e-12);
    EXPECT_NEAR(s.sigma_v, 0.5 * 2.0 * D / (f * std::sin(rad(theta))), 1e-12);
    EXPECT_NEAR(s.sigma_v / s.sigma_u, 1.0 / std::sin(rad(theta)), 1e-9);
    // Tangent-frame view vector points back to the eye (towards -y, up).
    EXPECT_NEAR(s.view_x, 0.0, 1e-12);
    EXPECT_NEAR(s.view_y, -std::cos(rad(theta)), 1e-12);
    EXPECT_NEAR(s.view_z, std::sin(rad(theta)), 1e-12);
    EXPECT_NEAR(parallax_y(s), -1.0 / std::tan(rad(theta)), 1e-9);
  }
}

// Straight down with roll 45: J is a rotation scaled by the pixel size p. The marginal footprint is
// s p; Dorn's axis-aligned bound of the rotated square is s p (cos 45 + sin 45) = s p sqrt 2.
TEST(RuntimeCamera, DornBoundVersusGaussianMarginal) {
  Camera cam = straight_down(1.0, 60, 32, 32);
  cam.roll_deg = 45;
  const double p = 2.0 * std::tan(rad(30.0)) / 32;
  FootprintOptions dorn, marginal;
  marginal.bound = FootprintBound::kGaussianMarginal;
  dorn.pixel_sigma = marginal.pixel_sigma = 0.5;
  const PlaneSample a = trace_pixel(cam, dorn, 5.5, 20.5), b = trace_pixel(cam, marginal, 5.5, 20.5);
  EXPECT_NEAR(a.sigma_u, 0.5 * p * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(a.sigma_v, 0.5 * p * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(b.sigma_u, 0.5 * p, 1e-12);
  EXPECT_NEAR(b.sigma_v, 0.5 * p, 1e-12);
  EXPECT_NEAR(std::abs(a.du_dx), p / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(a.rho, 0.0, 1e-12);  // a rotation keeps u and v uncorrelated
  // A grazing view with yaw 45: the footprint is stretched along a diagonal, so u and v correlate.
  Camera diag;
  diag.position = {0, 0, 1};
  diag.yaw_deg = 45;
  diag.pitch_deg = -20;
  const PlaneSample c = trace_pixel(diag, marginal, 256.0, 256.0);
  EXPECT_GT(c.rho, 0.5);  // both u and v grow along the view direction (+x+y)
}

TEST(RuntimeCamera, BatchMatchesSinglePixels) {
  Camera cam;
  cam.position = {1, 2, 1.2};
  cam.yaw_deg = -20;
  cam.pitch_deg = -12;
  cam.roll_deg = 5;
  cam.width = 40;
  cam.height = 30;
  FootprintOptions opt;
  opt.texture_scale = 5;
  const PixelRect rect{3, 4, 20, 25};
  std::vector<float> offsets(2 * 20 * 25);
  for (size_t i = 0; i < offsets.size(); ++i) offsets[i] = float(std::sin(0.37 * i)) * 0.5f;
  PlaneBatch batch;
  trace_plane(cam, opt, batch, rect, offsets.data());
  ASSERT_EQ(batch.size(), 20u * 25u);
  int hits = 0, misses = 0;
  for (int y = 4; y < 29; ++y) {
    for (int x = 3; x < 23; ++x) {
      const size_t i = size_t(y - 4) * 20 + (x - 3);
      const PlaneSample s = trace_pixel(cam, opt, x + 0.5 + offsets[2 * i], y + 0.5 + offsets[2 * i + 1]);
      ASSERT_EQ(bool(batch.hit[i]), s.hit) << x << "," << y;
      (s.hit ? hits : misses)++;
      auto near = [](float got, double want) { return std::abs(got - want) <= 1e-6 * (1 + std::abs(want)); };
      EXPECT_TRUE(near(batch.u[i], s.u) && near(batch.v[i], s.v) && near(batch.sigma_u[i], s.sigma_u) &&
                  near(batch.sigma_v[i], s.sigma_v) && near(batch.du_dy[i], s.du_dy) &&
                  near(batch.dv_dx[i], s.dv_dx) && near(batch.view_y[i], s.view_y) &&
                  near(batch.distance[i], s.distance) && near(batch.rho[i], s.rho))
          << x << "," << y;
    }
  }
  EXPECT_GT(hits, 0);
  EXPECT_GT(misses, 0);  // the rect straddles the horizon
  trace_plane(cam, opt, batch);
  EXPECT_EQ(batch.size(), 40u * 30u);
  EXPECT_THROW(trace_plane(cam, opt, batch, PixelRect{30, 0, 20, 5}), std::invalid_argument);
  cam.position.z = -1;
  EXPECT_THROW(trace_plane(cam, opt, batch), std::invalid_argument);
}

}  // namespace
