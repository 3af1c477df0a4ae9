// The footprint-LOD pair of tuned programs (lod.hpp) and what its sides may be: the scene's front
// points, and the plain program at 2..16 stratified samples (ssN, compiler::stratified_samples). Near
// pixels, where plain is nearly right, can buy their accuracy with a few samples and far ones with
// smoothing: circles_bumps reaches MSAA-16's error only so (ss4 on 94% of its pixels, a smoothed
// point beyond; docs/tuning.md, stop 36). One side must be smoothed: two supersamplers are the
// footprint-adaptive supersampler, the comparator (adaptive_supersampling.hpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "compiler/lir.hpp"
#include "tuner/cost_model.hpp"
#include "tuner/lod.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

struct LodSide {
  std::string label;          // the point's label, or ssN
  std::string schedule;       // compiler::schedule_to_text (the plain schedule for ssN)
  int samples = 1;            // stratified samples of the schedule (1: the schedule itself)
  bool smoothed = true;       // the schedule is not the plain one
  compiler::Program program;  // all its samples
  compiler::Program one;      // one of its samples: priced `samples` times (CostModel::sequential_cost)
  // ns per pixel under m: one program, or its samples one after another.
  double price(const CostModel& m) const;
};

// The points' sides (labels and schedules, in order) and then ss2 .. ss16 (kAdaptiveSampleCounts).
// Empty when a schedule does not lower (front points lower; a table change would show here).
std::vector<LodSide> lod_sides(const SceneTuner& t,
                               const std::vector<std::pair<std::string, compiler::Schedule>>& points);

// The fastest pair of `sides` with a smoothed side whose error over every pixel of every frame is <=
// target (lod_candidates by each side's all-pixel price, then fastest_on_own_pixels); near = -1
// when none reaches it.
LodChoice fastest_lod_pair(const SceneTuner& t, const std::vector<LodSide>& sides, double target);

}  // namespace bl::tuner
