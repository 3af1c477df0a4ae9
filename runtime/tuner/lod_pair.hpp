// Footprint pairs: two programs of one scene chosen per pixel by its footprint (lod.hpp), as a
// renderer picks shader variants by distance. Two kinds, one description:
// - the footprint-LOD pair of tuned programs: sides are the scene's front points and the plain
//   program at 2..16 stratified samples (ssN, compiler::stratified_samples), the far side smoothed.
//   Near pixels, where plain is nearly right, can buy their accuracy with a few samples; far ones,
//   where the pattern aliases, are smoothing's: circles_bumps reaches MSAA-16's error only so (ss4 on
//   94% of its pixels, a smoothed point beyond; docs/tuning.md, stop 36). A supersampled far side
//   would credit smoothing with the supersampler's work (fire_ripples: a nearly plain point near and
//   ss8 far is the adaptive supersampler's plain + ss8 within 0.2%);
// - the footprint-adaptive supersampler, the comparator (adaptive_supersampling.hpp): plain and ssN
//   only.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compiler/lir.hpp"
#include "tuner/cost_model.hpp"
#include "tuner/lod.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

// Sample counts of the supersampled sides (1: the plain program itself).
constexpr int kSupersampleCounts[] = {1, 2, 3, 4, 6, 8, 12, 16};

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

// A footprint pair as result.json keeps it (SceneResult::lod and ::adaptive_ss).
struct LodResult {
  // Labels: front points (frontNN), searchNN (row NN of front_search.csv, not measured), plain, or
  // ssN (the plain program at N stratified samples).
  std::string near, far;
  std::string near_schedule, far_schedule;  // compiler::schedule_to_text ("" in older adaptive_ss)
  int near_samples = 1, far_samples = 1;    // stratified samples of each schedule (1: the schedule)
  float limit = 0;                          // footprint (max of sigma_u, sigma_v) where `far` takes over
  double near_share = 0;                    // share of the hit pixels (all frames) below it
  double model_ns = 0;                      // near_share T(near) + (1 - near_share) T(far) + the dispatch
  double error = 0;                         // RMS display, every pixel of every frame
  double compiled_ns = -1;  // the pair compiled into one loop (jit), frame 0; -1 without a compiler
};

// A pair picked, with its two programs (to time, emit, render).
struct PickedPair {
  LodResult result;  // compiled_ns not set
  compiler::Program near, far;
};

// One point's side: nullopt when the schedule does not lower.
std::optional<LodSide> lod_side(const SceneTuner& t, const std::string& label,
                                const compiler::Schedule& schedule);

// The points' sides (labels and schedules, in order), then ss2 .. ss16. Empty when a schedule does
// not lower (front points lower; a table change would show here).
std::vector<LodSide> lod_sides(const SceneTuner& t,
                               const std::vector<std::pair<std::string, compiler::Schedule>>& points);

// The fastest pair of `sides` whose error over every pixel of every frame is <= target, with a
// smoothed far side when `smoothed_far` (lod_candidates by each side's all-pixel price, then
// fastest_on_own_pixels, lod_pricing.hpp); none when no pair reaches it.
std::optional<PickedPair> fastest_pair(const SceneTuner& t, const std::vector<LodSide>& sides, double target,
                                       bool smoothed_far);

}  // namespace bl::tuner
