// Greedy descent of a footprint-LOD pair (lod_pair.hpp) as one program: single-gene rule changes on
// either side (and fused pairs to one rule, as polish.hpp moves them) that lower the pair's model
// time while its sample error stays at most the start's. The front points a pair is built from were
// tuned for every pixel; each side then runs on only part of them, where much of its smoothing buys
// nothing (fire_bumps' near side is front03, tuned against the far rows' aliasing too), and a
// change that costs the far side error can be paid for by the near side. Both sides are priced on
// their own pixels (SceneTuner::cost_model_over) and their errors taken on the search sample's
// pixels below and above the limit.
#pragma once

#include "compiler/lir.hpp"
#include "tuner/polish.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

struct PolishedPair {
  compiler::Schedule near, far;
  double time_before = 0, time_after = 0;    // near_share T(near) + (1 - near_share) T(far), ns/px
  double error_before = 0, error_after = 0;  // RMS display over the search sample's pixels
  int steps = 0, evaluations = 0;
};

// From (near, far) switching at footprint `limit`, near_share of the hit pixels below it (on full
// images, as LodResult keeps it), keeping the pair's sample error at most error_scale (>= 1) times
// the start's: finalize passes the full-image headroom, MSAA-16's error over the pair's, and picks
// again on full images. The start itself when no change helps. Throws std::invalid_argument when
// near_share is outside [0, 1], error_scale below 1 (or NaN) or a schedule does not lower.
PolishedPair polish_pair(const SceneTuner& t, const compiler::Schedule& near, const compiler::Schedule& far,
                         float limit, double near_share, double error_scale = 1,
                         const PolishOptions& opt = {});

}  // namespace bl::tuner
