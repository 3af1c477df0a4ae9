// A pixel's footprint against the plane's edge (the horizon): how much of the pixel filter lands on
// the plane, and where to shade the part that does.
//
// A renderer resolves geometric edges by coverage (hardware MSAA shades once per pixel and resolves
// coverage per sample); this is that term for the one edge this scene model has. The ray direction
// d(px, py) = f F + (px - w/2) R - (py - h/2) U is affine in the image point, so the hit region
// {d.z < 0} is a half-plane of the image. For the pixel filter N(c, s^2 I) (s = pixel_sigma) the
// covered fraction is exactly Phi(h / s), h = the signed distance in pixels from c to the horizon line,
// positive on the plane's side. The shading point is the mean of the filter restricted to the plane:
// c + s phi(z) / Phi(z) n, z = h / s, n the unit normal towards the plane (the inverse Mills ratio).
// Without a horizon in the image (|grad d.z| = 0), with s = 0 or a finite max_distance the coverage
// is the centre's hit (0 or 1). Coverage below kMinCoverage counts as a miss and above 1 - kMinCoverage
// as a full hit shaded at the centre: that moves a pixel by at most 1e-3 of the sky/plane difference
// (below an 8-bit step) and keeps the far-field points, whose huge arguments float and double (GLSL and
// C++) round differently, out of all but the pixels that really straddle the horizon.
#pragma once

#include "camera/plane_hit.hpp"

namespace bl::camera {

inline constexpr double kMinCoverage = 1e-3;

// The pixel filter N((px, py), s^2 I) against the horizon (no max_distance): the fraction whose rays
// hit the plane, in [0, 1], and the mean image point of that part (the centre when the fraction is 0
// or 1 up to kMinCoverage).
struct Coverage {
  double fraction = 0;
  double px = 0, py = 0;
};
Coverage horizon_coverage(const Camera& cam, const Basis& b, double pixel_sigma, double px, double py);

// The pixel's trace for a smoothed shader: the plane sample at the covered part's mean, with
// PlaneSample::coverage set (hit is coverage > 0). Far from the horizon this is trace_pixel at the
// centre with coverage 1.
PlaneSample trace_footprint(const Camera& cam, const Basis& b, const FootprintOptions& opt, double px,
                            double py);

}  // namespace bl::camera
