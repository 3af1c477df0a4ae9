// The scene's observed argument magnitudes: for each atomic the plain program calls, the share of
// calls (over the pixel sample) whose argument |x| falls in each CostModel band. The cost model
// weights banded function costs by it (CostModel::band_share): fract at |x| ~ 1e4 costs ~10x fract
// at ~1, and which one a scene has is only known from its inputs.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "compiler/lir.hpp"
#include "tuner/pixel_sample.hpp"

namespace bl::tuner {

// Rows sum to 1; atomics whose calls saw no finite argument are absent. `plain` is the all-"none"
// program (its Call instructions are the atomics, their first argument is x): CostModel::kBands
// shares per atomic.
std::map<std::string, std::vector<double>> magnitude_profile(const compiler::Program& plain,
                                                             const PixelSample& sample);

// The same over the kernel entries f(x, sigma) a smoothed program (the all-Gaussian one) calls:
// kBands x kSigmaBands shares per atomic (index x_band * kSigmaBands + sigma_band).
std::map<std::string, std::vector<double>> joint_profile(const compiler::Program& smoothed,
                                                         const PixelSample& sample);

}  // namespace bl::tuner
