// Runs a lowered program on one pixel: per input (in the program's input order) its mean,
// footprint sd and screen gradient (gx, gy); returns the first output. Shared by the rule tests.
#pragma once

#include <vector>

#include "compiler/evaluator.hpp"

namespace bl::testing {

inline float run_one_pixel(const compiler::Program& p, const std::vector<float>& mean,
                           const std::vector<float>& sd, const std::vector<float>& gx,
                           const std::vector<float>& gy) {
  compiler::Batch b;
  b.count = 1;
  for (std::size_t j = 0; j < mean.size(); ++j) {
    b.mean.push_back(&mean[j]);
    b.sd.push_back(&sd[j]);
    b.grad_x.push_back(&gx[j]);
    b.grad_y.push_back(&gy[j]);
  }
  float out;
  compiler::Evaluator(p).run(b, {&out});
  return out;
}

}  // namespace bl::testing
