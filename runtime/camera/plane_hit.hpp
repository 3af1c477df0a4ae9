// Where a pixel's ray meets the ground plane, and the pixel's footprint in surface coordinates.
//
// Surface coordinates: (u, v) = texture_scale * (x, y) on the plane z = 0. Tangent frame: T = +x
// (the u direction), B = +y (v), N = +z (towards the camera, which is always above the plane).
//
// Footprint. J = [[du/dpx, du/dpy], [dv/dpx, dv/dpy]] is the exact derivative of the hit point with
// respect to the image coordinates (analytic, from the ray/plane intersection; py grows downward).
// If a pixel sample is offset by N(0, s^2 I) pixels (s = pixel_sigma, 0.5 px by default as in
// Yang & Barnes 2018, Sec. 4.3), then to first order (u, v) ~ N(., s^2 J J^T), whose marginal
// standard deviations are s * sqrt(du/dpx^2 + du/dpy^2) (FootprintBound::kGaussianMarginal).
// Dorn et al. 2015, Sec. 3.2 instead bound the pixel's parallelogram by its axis-aligned rectangle,
// whose extents are |ds/dx| + |ds/dy| and |dt/dx| + |dt/dy|, and use them as the widths of two 1D
// Gaussians (FootprintBound::kDornAxisAligned): sigma_u = s * (|du/dpx| + |du/dpy|). The two agree
// when the image axes map onto the (u, v) axes and Dorn's is up to sqrt(2) wider otherwise ("favors
// blurring over aliasing"). With s = 1 Dorn's widths are reproduced literally.
#pragma once

#include <limits>

#include "camera/camera.hpp"

namespace bl::camera {

enum class FootprintBound { kDornAxisAligned, kGaussianMarginal };

struct FootprintOptions {
  double texture_scale = 1.0;  // u = texture_scale * x, v = texture_scale * y
  double pixel_sigma = 0.5;    // s, in pixels
  FootprintBound bound = FootprintBound::kDornAxisAligned;
  double max_distance = std::numeric_limits<double>::infinity();  // farther hits count as misses
  // trace_plane without offsets (one sample per pixel, a smoothed shader's trace): resolve the
  // horizon by the pixel filter's coverage (camera/horizon_coverage.hpp) instead of the centre's hit.
  bool horizon_coverage = false;
};

struct PlaneSample {
  bool hit = false;  // false: background (ray parallel to or away from the plane, or too far);
                     // every other field is then 0
  double u = 0, v = 0;
  double distance = 0;                                // from the eye to the hit point, world units
  double view_x = 0, view_y = 0, view_z = 0;          // unit vector hit -> eye in (T, B, N); view_z > 0
  double du_dx = 0, du_dy = 0, dv_dx = 0, dv_dy = 0;  // per pixel; y is the downward image axis
  double sigma_u = 0, sigma_v = 0;                    // per FootprintOptions::bound
  double rho = 0;       // correlation of u and v under the linearized Gaussian pixel filter, in [-1, 1]
  double coverage = 0;  // the pixel's weight on the plane: 1 for a hit point, Phi(.) from trace_footprint
};

// Traces image point (px, py) (a pixel centre is (i + 0.5, j + 0.5); add a jitter offset for
// sub-pixel samples). Throws std::invalid_argument for an invalid camera (see validate).
PlaneSample trace_pixel(const Camera& cam, const FootprintOptions& opt, double px, double py);

// The same without the checks, for loops over many pixels: cam must be valid and b == basis(cam).
PlaneSample trace_pixel(const Camera& cam, const Basis& b, const FootprintOptions& opt, double px, double py);

// The parallax-mapping ratio (view_x / view_z, view_y / view_z) is what offset mapping multiplies
// by the height; it grows without bound toward the horizon.
inline double parallax_x(const PlaneSample& s) {
  return s.view_x / s.view_z;
}
inline double parallax_y(const PlaneSample& s) {
  return s.view_y / s.view_z;
}

}  // namespace bl::camera
