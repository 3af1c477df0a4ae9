// A cost model for a GPU, fitted on measured draws (blgpu_time's gpu_times.json) rather than
// calibrated: a fragment shader's functions are inlined, so nothing is called, spilled or chained
// as on a CPU, and a GPU prices its operations in other proportions (the H200 drew the suite's
// programs at 0.0016-0.21x their compiled-C++ time, median 0.0086; docs/gpu_timing.md, stop 42).
// The model keeps CostModel's form with only the throughput terms (an op or function price per
// call, the per-pixel overhead, the output stores) and a floor: a fragment costs at least the
// GPU's fragment rate (CostModel::floor_ns). Each price is the CPU calibration's times one global
// ratio, times (1 + d), with the d fitted by ridge-regularized least squares on relative errors:
// a function the draws never used keeps the scaled CPU price.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "compiler/lir.hpp"
#include "tuner/cost_model.hpp"

namespace bl::tuner {

// Coefficients of the priced names ("pixel", "output", op names, function C++ names) in
// CostModel::throughput(p) under a model without band, spill or pair prices.
using Features = std::map<std::string, double>;
Features throughput_features(const compiler::Program& p);
// n samples of a program's body in one fragment (MSAA-n and ssN in the shader): the body n times,
// the per-pixel overhead and output stores once, n - 1 adds per output (the sums), and "sample" = n
// (the loop's per-sample price): CostModel::sequential_cost's terms.
Features repeated(const Features& one, int n);

struct GpuSample {
  std::string scene, label;
  Features x;
  double measured_ns = 0;  // GPU ns per pixel
};

struct GpuFitOptions {
  double lambda = 1;            // ridge weight per fitted price (relative deviation from the prior)
  double floor_ns = 0;          // the fragment-rate floor (CostModel::floor_ns of the fitted model)
  double min_over_floor = 1.5;  // fit on draws at least this many floors (below, the floor hides T)
  double floor_norm = 0;        // CostModel::floor_norm of the fitted model (0: a hard max)
};

struct GpuFit {
  CostModel model;   // method "gpu-fit"; every price of the prior present
  double alpha = 0;  // the global GPU / CPU price ratio
  int used = 0;      // samples fitted on
  int fitted = 0;    // prices fitted (the rest: alpha x the prior's)
};

// Throws std::invalid_argument when no sample is above the floor or a feature has no prior price.
GpuFit fit_gpu_cost_model(const std::vector<GpuSample>& samples, const CostModel& prior,
                          const GpuFitOptions& o, const std::string& machine);

// CostModel::floored(sum of prices x features): what CostModel::cost gives a program of those
// features under a fitted GPU model.
double predict(const CostModel& m, const Features& x);

}  // namespace bl::tuner
