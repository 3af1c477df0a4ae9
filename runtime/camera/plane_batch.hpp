// Struct-of-arrays plane traces for a rectangle of pixels, to feed the renderer in batches.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "camera/plane_hit.hpp"

namespace bl::camera {

// Pixel rectangle; width or height < 0 means "to the image's edge".
struct PixelRect {
  int x0 = 0, y0 = 0, width = -1, height = -1;
};

// One entry per pixel of `rect`, row-major, index (y - y0) * width + (x - x0), row y0 first (rows
// grow downward as in bl::Image). The fields mean what PlaneSample's do, stored as float.
struct PlaneBatch {
  PixelRect rect;
  std::vector<std::uint8_t> hit;
  std::vector<float> u, v, sigma_u, sigma_v, rho;
  std::vector<float> du_dx, du_dy, dv_dx, dv_dy;
  std::vector<float> view_x, view_y, view_z;
  std::vector<float> distance;
  std::vector<float> coverage;  // the pixel's weight on the plane (PlaneSample::coverage); the rest is sky

  std::size_t size() const { return hit.size(); }
  void resize(std::size_t n);
  // The entries at `indices` (in that order), e.g. a pixel sample; `rect` is kept as is.
  PlaneBatch gather(const std::vector<int>& indices) const;
};

// Fills `out` (reusing its storage) for every pixel of `rect`. `offsets`, when given, holds 2 floats
// per pixel of the rect in the same order: the sample's offset from the pixel centre in pixels
// (jittered samples); nullptr samples the centres. Throws std::invalid_argument for a rect outside
// the image or an invalid camera. Without offsets and with opt.horizon_coverage each pixel is traced by
// trace_footprint (hit = coverage > 0); otherwise by trace_pixel (coverage = hit).
void trace_plane(const Camera& cam, const FootprintOptions& opt, PlaneBatch& out, PixelRect rect = {},
                 const float* offsets = nullptr);

}  // namespace bl::camera
