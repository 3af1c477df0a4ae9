// Footprint LOD: two tuned programs of one scene, chosen per pixel by the pixel's footprint (the
// larger of the surface coordinates' sds, sigma_u and sigma_v): `near` where it is below `limit`,
// `far` elsewhere. A renderer picks shader variants by distance the same way. Near pixels see the
// pattern's features many pixels wide, where a cheap program (often plain) is already close to the
// truth; far pixels need the accurate one. fire_none's fastest single program at MSAA-16's error
// loses to MSAA on view 1's far rows and wins on its near rows; the pair pays for accuracy only
// where it is needed.
#pragma once

#include <vector>

namespace bl::tuner {

struct LodChoice {
  int near = -1, far = -1;  // indices into the candidate programs; -1: none reaches the target
  float limit = 0;          // footprint at which `far` takes over
  double near_share = 0;    // share of the hit pixels below the limit
  double model_ns = 0;      // near_share x T(near) + (1 - near_share) x T(far) + dispatch_ns
  double error = 0;         // RMS display error of the pair over the same pixels as the inputs
};

// The fastest pair (then the lower error) whose error is <= target. sq[k][i]: program k's squared
// display error of hit pixel i summed over its three channels (PixelSample::pixel_sq); fp[i]: that
// pixel's footprint; model_ns[k]: program k's model time; miss_sq: the missed pixels' share of the
// sum; pixels: all pixels counted (hit or not), so error = sqrt((miss_sq + sum) / (3 pixels)).
// Limits tried: the footprints at `limits` evenly spaced quantiles of fp (each a boundary between
// distinct footprints). Throws std::invalid_argument on ragged inputs.
LodChoice fastest_lod(const std::vector<std::vector<double>>& sq, const std::vector<float>& fp,
                      const std::vector<double>& model_ns, double miss_sq, long pixels, double target,
                      double dispatch_ns, int limits = 64);
// Every pair and limit that reaches the target, fastest first (then the lower error), at most `keep`:
// model_ns is each program's price over all pixels, and a program costs more on some pixels than on
// others (the far ones), so the caller re-prices these on the pixels each program gets.
std::vector<LodChoice> lod_candidates(const std::vector<std::vector<double>>& sq,
                                      const std::vector<float>& fp, const std::vector<double>& model_ns,
                                      double miss_sq, long pixels, double target, double dispatch_ns,
                                      int limits, int keep);

}  // namespace bl::tuner
