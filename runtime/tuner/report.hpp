// Tuning reports: per scene a CSV and a Markdown table of the front and the baselines, a gnuplot
// Pareto plot (model time and measured evaluator time against error), speed-ups against MSAA at
// equal error; for a suite, a summary table over scenes.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "tuner/finalize.hpp"

namespace bl::tuner {

struct Speedup {
  int msaa = 0;
  double msaa_error = 0;
  int front_index = -1;            // fastest front point with error <= MSAA's; -1 when none reaches it
  double model = 0, measured = 0;  // MSAA time / front point time (cost model, measured)
  bool compiled = false;           // `measured` is compiled code's time (else the evaluator's)
};

// The time a report quotes for m: compiled ms per frame when measured, else the evaluator's.
double measured_ms(const Measured& m);

std::vector<Speedup> speedups(const SceneResult& r);
// The footprint-LOD pair's speed-up at MSAA-16's error (SceneResult::lod): MSAA-16's time over the
// pair's, by the model and measured (compiled; 0 when either time is missing). Both 0 without a pair.
struct LodSpeedup {
  double model = 0, measured = 0;
};
LodSpeedup lod_speedup16(const SceneResult& r);
// Against stratified supersampling (the ssN baselines): the one with the fewest samples whose error is
// at most MSAA-16's, and ours at that error: the point speedup16 reads or the footprint-LOD pair,
// whichever is faster (by compiled time for `measured`, by the model for `model`). measured = ssN's
// compiled time / ours (0 when a compiled time is missing); model = ssN's model time / ours (finalize
// prices ssN with CostModel::sequential_cost). label "" (and zeros) when no ssN reaches that error
// (results before stop 34 have no ssN); ours_* and the ratios 0 when no point of ours reaches it.
struct StratifiedSpeedup {
  std::string label;                            // ssN
  double ss_ns = 0, ours_ns = 0, measured = 0;  // compiled
  double ss_model_ns = 0, ours_model_ns = 0, model = 0;
};
StratifiedSpeedup stratified_speedup16(const SceneResult& r);
// Ours at MSAA-16's error: the fastest front point there (speedup16's) or the footprint-LOD pair,
// whichever is faster, by the model and by compiled time (0: none reaches it, or not timed).
struct Ours16 {
  double model_ns = 0, compiled_ns = 0;
};
Ours16 ours16(const SceneResult& r);
// Against the footprint-adaptive stratified supersampler (SceneResult::adaptive_ss): its time over
// ours16's, by the model and measured (compiled); 0 where either is missing.
struct AdaptiveSpeedup {
  double model = 0, measured = 0;
};
AdaptiveSpeedup adaptive_speedup16(const SceneResult& r);
// The speed-up at MSAA-16's error (msaa 0 when the scene has no MSAA-16 baseline).
Speedup speedup16(const SceneResult& r);

// Where program p's model time goes under m (bltune --explain, and the report's point at MSAA-16's
// error), in Markdown: each function's calls and price, inline arithmetic, values kept across calls
// and the pixel loop, dearest first (rows sum to the throughput T); the latency chain and the cost;
// then p against `plain`: MSAA-16 costs 16 plain programs, so 10x less time at its error asks for at
// most 1.6x plain.
std::string time_breakdown_markdown(const CostModel& m, const compiler::Program& p,
                                    const compiler::Program& plain);

// Writes dir/front.csv, dir/report.md and dir/pareto.png (the plot is skipped, with a line in the
// Markdown, when gnuplot is missing).
void write_scene_report(const SceneResult& r, const std::string& dir);

// The cost model against compiled code over a scene's measured points (front and baselines):
// median and largest |model / compiled - 1| (NaN when no compiled time exists), and the points
// outside issue 14's tolerance (|model / compiled - 1| > kModelTolerance) as "label (ratio)".
constexpr double kModelTolerance = 0.25;
struct ModelAccuracy {
  int points = 0;
  double median = NAN, worst = NAN;
  std::vector<std::string> outside;
};
ModelAccuracy model_accuracy(const SceneResult& r);

// What a speed-up of `factor` over MSAA-16 at its error, by the model (issue 13's count), still
// needs: the fastest front point at <= MSAA-16's error and the share of its model time to cut, and
// the lowest-error point among those at >= factor x less model time and the share of its error to
// cut. A cut <= 0 means that side is already there.
struct TenfoldGap {
  double msaa16_error = NAN;
  int at_error = -1;       // front index, -1 when no point reaches MSAA-16's error
  double time_cut = NAN;   // 1 - (MSAA-16 model time / factor) / its model time
  int at_time = -1;        // front index, -1 when no point is that fast
  double error_cut = NAN;  // 1 - MSAA-16's error / its error
};
TenfoldGap tenfold_gap(const SceneResult& r, double factor = 10);

// Writes dir/summary.md and dir/summary.csv over the scenes.
void write_suite_summary(const std::vector<SceneResult>& rs, const std::string& dir);

}  // namespace bl::tuner
