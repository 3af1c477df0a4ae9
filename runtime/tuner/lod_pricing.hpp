// Footprint-LOD pairs priced on their own pixels: lod_candidates (lod.hpp) ranks pairs by each
// program's price over all pixels, but a program costs more on some pixels than on others (the far
// ones), so the pick re-prices each candidate with the near program under the cost model of the
// search sample's pixels below the limit and the far one above (SceneTuner::cost_model_over).
// Used by fastest_pair (lod_pair.hpp), which picks both the LOD pair of tuned programs and the
// footprint-adaptive supersampler.
#pragma once

#include <functional>
#include <vector>

#include "tuner/cost_model.hpp"
#include "tuner/lod.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

// The per-pixel dispatch a pair adds: the footprint's max and the branch's compare.
double lod_dispatch_ns(const CostModel& m);

// The fastest of `cands` with model_ns = near_share price(near model, near) + (1 - near_share)
// price(far model, far) + dispatch_ns; price(m, k) is candidate program k's ns per pixel under m.
// near = -1 when `cands` is empty.
LodChoice fastest_on_own_pixels(const SceneTuner& t, const std::vector<LodChoice>& cands,
                                const std::function<double(const CostModel&, int)>& price,
                                double dispatch_ns);

}  // namespace bl::tuner
