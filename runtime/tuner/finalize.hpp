// After the search: Nelder-Mead on the front points, errors on full images, timings of the emitted
// code (the emitted C++ compiled with -O3 -march=native at run time, the time the reports quote; the batch
// evaluator; GLSL on the OpenGL driver only when asked), the baselines (plain, MSAA 2..32, all-Dorn,
// all-adaptive-Gaussian) and images of chosen variants.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "jit/jit.hpp"
#include "tuner/lod_pair.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

struct Measured {
  std::string label;
  std::string schedule;  // compiler::schedule_to_text; "all RULE" or "plain x N ..." for baselines
  int msaa = 0;          // MSAA sample count (baselines), 0 otherwise
  // ssN baselines: N, the plain program at N fixed stratified offsets inside the shader
  // (compiler/supersample.hpp); 0 otherwise. model_ns is CostModel::sequential_cost (the samples one
  // after another, as compiled per-pixel code runs them).
  int supersample = 0;
  double model_ns = 0;      // cost model, ns per pixel
  double search_error = 0;  // on the pixel sample (front points; NaN for baselines)
  double error = 0;         // RMS display (display_error), every pixel of every frame
  double psnr = 0;
  std::size_t nonfinite = 0;          // pixels (all frames) with a NaN or infinite channel
  std::size_t out_of_range = 0;       // other pixels with a channel outside the truth's range (pixel_check)
  double eval_ms = 0;                 // batch evaluator, single thread, ms per frame, frame 0
  double compiled_ns = -1;            // compiled emitted C++ (-O3), single thread, ns per pixel, frame 0;
  double compiled_ms = -1;            //   and ms per frame; -1 when no compiler (jit::Error)
  double glsl_ms = -1;                // GLSL ms per frame on the GL driver; -1 when not measured
  bool refined = false;               // Nelder-Mead improved it
  std::map<std::string, double> mix;  // share of genes per rule family
};

struct SceneResult {
  std::string scene;
  std::string graph_hash;  // compiler::graph_hash_text of the traced graph the schedules are for
  int nodes = 0, genes = 0, pixels = 0, frames = 0;
  double search_seconds = 0, finalize_seconds = 0;
  int evaluations = 0;
  long rejected_nonfinite = -1;     // search evaluations infeasible for NaN/inf on the sample (-1: unknown)
  std::vector<Measured> front;      // sorted by model time
  std::vector<Measured> baselines;  // plain, msaa2..32, dorn, gaussian
  std::string gl_renderer;          // "" when GLSL was not timed
  // The model's machine when it is not a calibration of this CPU (bltune --cost-machine: a GPU model
  // fitted on draws, "NVIDIA H200 (GLSL, fitted)"); "" for this CPU's.
  std::string cost_machine;
  std::string compiled_note;  // why compiled times are missing ("" when measured)
  // Markdown: where the model time of the fastest front point at MSAA-16's error goes
  // (time_breakdown_markdown, report.hpp); "" when no point reaches that error.
  std::string anchor_breakdown;
  // The fastest footprint-LOD pair (lod_pair.hpp) at MSAA-16's error, of the measured front points,
  // the search's front points and supersampled plain; none: no pair beats the single points there.
  std::optional<LodResult> lod;
  // The footprint-adaptive stratified supersampler at MSAA-16's error (adaptive_supersampling.hpp);
  // none when no pair of sample counts reaches it, or in results before stop 35.
  std::optional<LodResult> adaptive_ss;
};

// The stratified supersampling baselines (ssN) finalize measures beside MSAA-N.
constexpr int kSupersampleBaselines[] = {4, 8, 16};

struct FinalizeOptions {
  bool glsl = false;    // time the GLSL when a driver exists (opt-in: llvmpipe compiles take minutes)
  int max_points = 12;  // at most this many front points are refined and measured (pick_front_points)
  std::string out_dir;  // images go here when non-empty
  int trials = 9;       // timing trials (minimum kept)
  jit::Options jit;     // compiler, flags, object cache of the compiled-code timings
  bool polish = true;   // greedy descent from the points at MSAA-16's error (polish.hpp)
};

SceneResult finalize(const SceneTuner& t, const std::vector<Point>& front, const FinalizeOptions& opt);

// Which search-front points finalize refines and measures (indices, ascending): for each target
// error e (MSAA 4, 8 and 16's) and each margin m of kAnchorMargins, the cheapest point whose search
// error is <= m e (the speed-up at that error is read off them: the search error is measured on
// sampled pixels, and a point just under e there often lands just over it in the full render, so a
// point with room to spare is measured too; spacing alone skipped checkerboard_none's all-box point,
// and two points just under 1.15 e skipped it again), then points spread evenly over the front, both
// ends kept, up to k in all.
constexpr double kAnchorMargins[] = {1.15, 1.0, 0.8};
std::vector<int> pick_front_points(const std::vector<Point>& front, int k,
                                   const std::vector<double>& targets);

std::map<std::string, double> rule_mix(const SceneTuner& t, const compiler::Schedule& s);
std::string rule_family(const rules::Rule& r);  // "none", "gaussian(rho=0)", "mc", "rule1", ...

}  // namespace bl::tuner
