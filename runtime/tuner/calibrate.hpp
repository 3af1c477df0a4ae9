// Calibration of the cost model: times every LOp and every generated function in compiled code (one
// translation unit of loop kernels, one per op and function, built with -O3 by bl::jit: the code a
// renderer runs), at each magnitude band of |x| for functions of an atomic's argument. Where no C++
// compiler exists, the batch evaluator is timed instead (method "evaluator", with a warning).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "jit/jit.hpp"
#include "tuner/cost_model.hpp"

namespace bl::tuner {

struct CalibrationOptions {
  int pixels = 4096;  // batch size per timing (16 evaluator blocks)
  int copies = 16;    // instructions under test per program (the rest is amortized overhead)
  double min_ms = 4;  // each timing repeats the batch until it took at least this long
  int trials = 3;     // the minimum over trials is kept (least disturbed by other load)
  std::string only;   // when non-empty: calibrate only entries whose name contains this
  // Compiled calibration: inputs ordered in 64-pixel runs as along an image row (false: i.i.d., which
  // mispredicts regime branches a frame predicts; kept for comparison).
  bool scanlines = true;
  enum class Method { Compiled, Evaluator } method = Method::Compiled;
  jit::Options jit;  // compiler and object cache of the compiled calibration
};

// The input arrays an instruction of `arity` operands reads in both calibrations: (mean, spread)
// pairs (arrays 0/2 means, 1/3 sds, 5 a variance when spread_is_var), then a small value (4).
std::vector<int> calibration_args(int arity, bool spread_is_var);
// A function's: stat rules read (mean, variance) pairs, kernel and stat entries (x, sd).
std::vector<int> calibration_args(const compiler::Function& f);

// Measures a fresh model for this machine (cpu_model()). `progress` (optional) gets each name.
// Method::Compiled falls back to the evaluator (and says so on stderr) when the compiler is missing.
CostModel calibrate(const CalibrationOptions& opt = {},
                    const std::function<void(const std::string&, double)>& progress = {});

// The compiled-code calibration alone (throws jit::Error when the compiler is missing or fails).
CostModel calibrate_compiled(const CalibrationOptions& opt,
                             const std::function<void(const std::string&, double)>& progress = {});

// The model for this machine from `path`, calibrating (and saving) first when the file lacks this
// machine or any current op/function (new generated functions land from other branches).
// `method`: the calibration wanted (a file calibrated otherwise is recalibrated; Compiled falls
// back to the evaluator without a compiler).
CostModel load_or_calibrate(const std::string& path, bool verbose,
                            CalibrationOptions::Method method = CalibrationOptions::Method::Compiled);

}  // namespace bl::tuner
