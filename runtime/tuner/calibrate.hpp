// Calibration of the cost model: times every LOp and every generated function through the batch
// evaluator (the code path the tuner and render_smoothed use) on realistic inputs.
#pragma once

#include <functional>
#include <string>

#include "tuner/cost_model.hpp"

namespace bl::tuner {

struct CalibrationOptions {
  int pixels = 4096;  // batch size per timing (16 evaluator blocks)
  int copies = 16;    // instructions under test per program (the rest is amortized overhead)
  double min_ms = 4;  // each timing repeats the batch until it took at least this long
  int trials = 3;     // the minimum over trials is kept (least disturbed by other load)
  std::string only;   // when non-empty: calibrate only entries whose name contains this
};

// Measures a fresh model for this machine (cpu_model()). `progress` (optional) gets each name.
CostModel calibrate(const CalibrationOptions& opt = {},
                    const std::function<void(const std::string&, double)>& progress = {});

// The model for this machine from `path`, calibrating (and saving) first when the file lacks this
// machine or any current op/function (new generated functions land from other branches).
CostModel load_or_calibrate(const std::string& path, bool verbose);

}  // namespace bl::tuner
