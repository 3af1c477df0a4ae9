#include "camera/plane_batch.hpp"

#include <stdexcept>
#include <string>

#include "camera/horizon_coverage.hpp"

namespace bl::camera {

namespace {
// Every float field, for loops that treat them alike.
constexpr std::vector<float> PlaneBatch::*kFloatFields[] = {
    &PlaneBatch::u,        &PlaneBatch::v,       &PlaneBatch::sigma_u, &PlaneBatch::sigma_v,
    &PlaneBatch::rho,      &PlaneBatch::du_dx,   &PlaneBatch::du_dy,   &PlaneBatch::dv_dx,
    &PlaneBatch::dv_dy,    &PlaneBatch::view_x,  &PlaneBatch::view_y,  &PlaneBatch::view_z,
    &PlaneBatch::distance, &PlaneBatch::coverage};
}  // namespace

void PlaneBatch::resize(std::size_t n) {
  hit.assign(n, 0);
  for (auto field : kFloatFields) (this->*field).assign(n, 0.0f);
}

PlaneBatch PlaneBatch::gather(const std::vector<int>& indices) const {
  PlaneBatch out;
  out.rect = rect;
  out.hit.reserve(indices.size());
  for (int i : indices) out.hit.push_back(hit.at(i));
  for (auto field : kFloatFields) {
    (out.*field).reserve(indices.size());
    for (int i : indices) (out.*field).push_back((this->*field).at(i));
  }
  return out;
}

void trace_plane(const Camera& cam, const FootprintOptions& opt, PlaneBatch& out, PixelRect rect,
                 const float* offsets) {
  validate(cam);
  if (rect.width < 0) rect.width = cam.width - rect.x0;
  if (rect.height < 0) rect.height = cam.height - rect.y0;
  if (rect.x0 < 0 || rect.y0 < 0 || rect.width < 0 || rect.height < 0 || rect.x0 + rect.width > cam.width ||
      rect.y0 + rect.height > cam.height) {
    throw std::invalid_argument("trace_plane: rect (" + std::to_string(rect.x0) + ", " +
                                std::to_string(rect.y0) + ") " + std::to_string(rect.width) + "x" +
                                std::to_string(rect.height) + " is outside the " + std::to_string(cam.width) +
                                "x" + std::to_string(cam.height) + " image");
  }
  const Basis b = basis(cam);
  out.rect = rect;
  out.resize(std::size_t(rect.width) * rect.height);
  std::size_t i = 0;
  for (int y = rect.y0; y < rect.y0 + rect.height; ++y) {
    for (int x = rect.x0; x < rect.x0 + rect.width; ++x, ++i) {
      const double ox = offsets ? offsets[2 * i] : 0.0, oy = offsets ? offsets[2 * i + 1] : 0.0;
      const PlaneSample s = offsets == nullptr && opt.horizon_coverage
                                ? trace_footprint(cam, b, opt, x + 0.5, y + 0.5)
                                : trace_pixel(cam, b, opt, x + 0.5 + ox, y + 0.5 + oy);
      if (!s.hit) continue;  // resize() left zeros
      out.hit[i] = 1;
      out.u[i] = float(s.u);
      out.v[i] = float(s.v);
      out.sigma_u[i] = float(s.sigma_u);
      out.sigma_v[i] = float(s.sigma_v);
      out.rho[i] = float(s.rho);
      out.du_dx[i] = float(s.du_dx);
      out.du_dy[i] = float(s.du_dy);
      out.dv_dx[i] = float(s.dv_dx);
      out.dv_dy[i] = float(s.dv_dy);
      out.view_x[i] = float(s.view_x);
      out.view_y[i] = float(s.view_y);
      out.view_z[i] = float(s.view_z);
      out.distance[i] = float(s.distance);
      out.coverage[i] = float(s.coverage);
    }
  }
}

}  // namespace bl::camera
