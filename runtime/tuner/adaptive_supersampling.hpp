// Footprint-adaptive stratified supersampling: the strongest comparator built from supersampling
// alone. Two plain supersamplers (the plain program, or ssN of compiler/supersample.hpp) chosen per
// pixel by its footprint, as the footprint LOD chooses two tuned programs (lod.hpp): few samples where
// the footprint is small, more where it is large. Picked like the LOD pair (the fastest pair whose
// error over every pixel is at most the target, each side priced on its own pixels, ssN sample by
// sample: CostModel::sequential_cost), so smoothing is compared with supersampling that adapts the
// same way. On the suite it reaches MSAA-16's error at a median 65% of uniform ss8's model time
// (docs/tuning.md, stop 35).
#pragma once

#include <optional>

#include "compiler/lir.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

// Sample counts the pair chooses from (1: the plain program).
constexpr int kAdaptiveSampleCounts[] = {1, 2, 3, 4, 6, 8, 12, 16};

struct AdaptiveSupersampling {
  int near_samples = 0, far_samples = 0;  // below and above `limit` (1: plain)
  float limit = 0;                        // footprint (max of sigma_u, sigma_v) where `far` takes over
  double near_share = 0;                  // share of the hit pixels (all frames) below it
  double model_ns = 0;                    // as LodResult::model_ns
  double error = 0;                       // RMS display, every pixel of every frame
  double compiled_ns = -1;                // the pair compiled into one loop, frame 0; -1: not timed
};

// The fastest pair at error <= target (none when no pair reaches it); compiled_ns is not set here.
std::optional<AdaptiveSupersampling> adaptive_supersampling(const SceneTuner& t, double target);

}  // namespace bl::tuner
