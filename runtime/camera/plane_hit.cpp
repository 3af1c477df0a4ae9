#include "camera/plane_hit.hpp"

#include <cmath>

namespace bl::camera {
namespace {

// Hit point of E + t d on z = 0 is P = E - (E_z / d_z) d. Differentiating along a direction of the
// image plane in which d changes by dd: dP = t * (dd - d * dd_z / d_z), with t = -E_z / d_z.
Vec3d plane_differential(double t, Vec3d d, Vec3d dd) {
  return t * (dd - (dd.z / d.z) * d);
}

}  // namespace

PlaneSample trace_pixel(const Camera& cam, const FootprintOptions& opt, double px, double py) {
  validate(cam);
  return trace_pixel(cam, basis(cam), opt, px, py);
}

PlaneSample trace_pixel(const Camera& cam, const Basis& b, const FootprintOptions& opt, double px,
                        double py) {
  const Vec3d d = ray_direction(cam, b, px, py);
  PlaneSample s;
  if (!(d.z < 0)) return s;  // parallel to, or pointing away from, the plane below the camera
  const double t = -cam.position.z / d.z;
  const double len = length(d);
  if (!(t * len <= opt.max_distance)) return s;
  const Vec3d hit = cam.position + t * d;
  const Vec3d dpx = plane_differential(t, d, b.right);
  const Vec3d dpy = plane_differential(t, d, -1.0 * b.up);

  const double k = opt.texture_scale;
  s.hit = true;
  s.coverage = 1;
  s.u = k * hit.x;
  s.v = k * hit.y;
  s.distance = t * len;
  s.view_x = -d.x / len;
  s.view_y = -d.y / len;
  s.view_z = -d.z / len;
  s.du_dx = k * dpx.x;
  s.du_dy = k * dpy.x;
  s.dv_dx = k * dpx.y;
  s.dv_dy = k * dpy.y;

  const double norm_u = std::hypot(s.du_dx, s.du_dy), norm_v = std::hypot(s.dv_dx, s.dv_dy);
  if (opt.bound == FootprintBound::kDornAxisAligned) {
    s.sigma_u = opt.pixel_sigma * (std::abs(s.du_dx) + std::abs(s.du_dy));
    s.sigma_v = opt.pixel_sigma * (std::abs(s.dv_dx) + std::abs(s.dv_dy));
  } else {
    s.sigma_u = opt.pixel_sigma * norm_u;
    s.sigma_v = opt.pixel_sigma * norm_v;
  }
  // cov(u, v) = s^2 (J J^T)_01; rho does not depend on s.
  if (norm_u > 0 && norm_v > 0) s.rho = (s.du_dx * s.dv_dx + s.du_dy * s.dv_dy) / (norm_u * norm_v);
  return s;
}

}  // namespace bl::camera
