// The cost model's out-of-order window (CostModel::window_ns) fitted to measured programs. The
// calibration measures the window on one kernel (8 chained libm sin calls per pixel); compiled
// shader programs, mostly inline arithmetic between fewer calls, overlap more pixels than that, so
// with the kernel's window the model over-priced every latency-bound plain program (bricks, ripples:
// model / compiled 1.4-1.6) and with them every MSAA baseline, which inflated model speed-ups. The
// fit times the plain (all-"none") program of each given scene, compiled with -O3 as a renderer
// runs it, and keeps the window that prices them best: one number fitted on plain programs, checked
// on the smoothed ones (bench/cost_model_check).
#pragma once

#include <string>
#include <vector>

#include "jit/jit.hpp"
#include "tuner/scene_tuner.hpp"

namespace bl::tuner {

struct WindowSample {
  std::string name;          // the scene
  double throughput_ns = 0;  // CostModel::throughput of the program under the scene's profile
  double path_ns = 0;        // CostModel::critical_path
  double measured_ns = 0;    // compiled code, ns per pixel (minimum over trials)
};

// The plain program of t's scene compiled (-O3, bl::jit) and timed over frame 0's pixel inputs, with
// t's cost model (the scene's magnitude profile). Throws jit::Error when no compiler works.
WindowSample measure_plain(const SceneTuner& t, const jit::Options& jit, int trials);

struct WindowFit {
  double window_ns = 0;
  // Over the samples, at the fitted window and at the one it replaces: mean |log(model/measured)|
  // and the count within 25% (kModelTolerance).
  double mean_abs_log = 0, previous_mean_abs_log = 0;
  int within = 0, previous_within = 0;
  // Every program prices within 0.1% of its throughput at the fitted window: any larger window fits
  // as well, the samples only bound it from below.
  bool lower_bound_only = false;
};

// The window on a log grid from 4 to 1024 ns (16 steps per octave) minimizing the mean
// |log(model/measured)| of the samples, model = CostModel::latency_bound; ties go to the smaller
// window. Throws std::invalid_argument with fewer than 3 samples or a non-positive time.
WindowFit fit_window(const std::vector<WindowSample>& samples, double previous_window_ns);

}  // namespace bl::tuner
