#include "render/frame.hpp"

#include <stdexcept>

namespace bl::render {

camera::Camera make_camera(const scene::Scene& s, int view) {
  if (view < 0 || view >= static_cast<int>(s.views.size()))
    throw std::out_of_range("scene " + s.name + " has no view " + std::to_string(view));
  camera::Camera c;
  c.position = {s.camera_position[0], s.camera_position[1], s.camera_position[2]};
  c.yaw_deg = s.views[view].yaw;
  c.pitch_deg = s.views[view].pitch;
  c.roll_deg = s.views[view].roll;
  c.vfov_deg = s.fov_deg;
  c.width = s.width;
  c.height = s.height;
  camera::validate(c);
  return c;
}

camera::FootprintOptions footprint_options(const scene::Scene& s) {
  camera::FootprintOptions o;
  o.texture_scale = s.uv_scale;
  o.pixel_sigma = s.sigma_px;
  o.bound = s.footprint_bound == scene::FootprintBound::Marginal ? camera::FootprintBound::kGaussianMarginal
                                                                 : camera::FootprintBound::kDornAxisAligned;
  o.horizon_coverage = true;  // one sample per pixel resolves the horizon by the filter's coverage
  return o;
}

shaders::Inputs<float> native_inputs(const scene::Scene& s, const camera::PlaneSample& p, double time) {
  shaders::Inputs<float> in;
  in.u = static_cast<float>(p.u);
  in.v = static_cast<float>(p.v);
  in.time = static_cast<float>(time);
  in.view = {static_cast<float>(p.view_x), static_cast<float>(p.view_y), static_cast<float>(p.view_z)};
  in.light = {static_cast<float>(s.light_dir[0]), static_cast<float>(s.light_dir[1]),
              static_cast<float>(s.light_dir[2])};
  in.textures = &s.textures;
  return in;
}

}  // namespace bl::render
