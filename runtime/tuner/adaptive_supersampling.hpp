// Footprint-adaptive stratified supersampling: the strongest comparator built from supersampling
// alone. Two plain supersamplers (the plain program, or ssN of compiler/supersample.hpp) chosen per
// pixel by its footprint, as the footprint LOD chooses two tuned programs (lod_pair.hpp): few samples
// where the footprint is small, more where it is large. Picked like the LOD pair (the fastest pair
// whose error over every pixel is at most the target, each side priced on its own pixels, ssN sample
// by sample: CostModel::sequential_cost), so smoothing is compared with supersampling that adapts the
// same way. On the suite it reaches MSAA-16's error at a median 65% of uniform ss8's model time
// (docs/tuning.md, stop 35).
#pragma once

#include <optional>

#include "tuner/lod_pair.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

// The fastest pair of plain, ss2 .. ss16 (kSupersampleCounts) at error <= target, sides labelled
// plain or ssN; none when no pair reaches it.
std::optional<PickedPair> adaptive_supersampling(const SceneTuner& t, double target);

}  // namespace bl::tuner
