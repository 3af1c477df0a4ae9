#include "camera/horizon_coverage.hpp"

#include <cmath>
#include <limits>

namespace bl::camera {
namespace {

struct Horizon {
  bool present = false;
  double h = 0;           // signed distance of the point to the horizon line, pixels, > 0 on the plane
  double nx = 0, ny = 0;  // unit normal of the line towards the plane, image coordinates
};

Horizon horizon_of(const Camera& cam, const Basis& b, double px, double py) {
  // d.z = f F.z + (px - w/2) R.z - (py - h/2) U.z: gradient (R.z, -U.z) in the image.
  const double gx = b.right.z, gy = -b.up.z, g = std::hypot(gx, gy);
  Horizon out;
  if (!(g > 0)) return out;
  const double dz = ray_direction(cam, b, px, py).z;
  out.present = true;
  out.h = -dz / g;
  out.nx = -gx / g, out.ny = -gy / g;
  return out;
}

double phi(double z) {
  return 0.3989422804014327 * std::exp(-0.5 * z * z);
}
double Phi(double z) {
  return 0.5 * std::erfc(-z * 0.7071067811865476);
}

}  // namespace

Coverage horizon_coverage(const Camera& cam, const Basis& b, double pixel_sigma, double px, double py) {
  const Horizon hz = horizon_of(cam, b, px, py);
  Coverage c{0, px, py};
  if (!hz.present || !(pixel_sigma > 0)) {
    c.fraction = ray_direction(cam, b, px, py).z < 0 ? 1.0 : 0.0;
    return c;
  }
  const double z = hz.h / pixel_sigma;
  c.fraction = Phi(z);
  if (c.fraction >= kMinCoverage && c.fraction <= 1 - kMinCoverage) {
    const double t = pixel_sigma * phi(z) / c.fraction;  // E[offset along n | on the plane]
    c.px += t * hz.nx, c.py += t * hz.ny;
  }
  return c;
}

PlaneSample trace_footprint(const Camera& cam, const Basis& b, const FootprintOptions& opt, double px,
                            double py) {
  if (opt.max_distance < std::numeric_limits<double>::infinity()) {
    PlaneSample p = trace_pixel(cam, b, opt, px, py);
    p.coverage = p.hit ? 1.0 : 0.0;
    return p;
  }
  const Coverage c = horizon_coverage(cam, b, opt.pixel_sigma, px, py);
  if (c.fraction < kMinCoverage) return PlaneSample{};
  PlaneSample p = trace_pixel(cam, b, opt, c.px, c.py);
  if (c.fraction <= 1 - kMinCoverage) p.coverage = p.hit ? c.fraction : 0.0;
  if (!p.hit) p.coverage = 0;
  return p;
}

}  // namespace bl::camera
