// Supersampling as a program: the plain program at N fixed offsets of the pixel, each input moved
// along its screen gradient (m + gx ox + gy oy, the pixel's linearized camera), the outputs averaged.
// It is supersampling inside one shader call with a fixed stratified pattern (as GPU MSAA uses fixed
// sample positions), a program like any other (C++, GLSL, evaluator, cost model). blrender
// --supersample N renders it beside MSAA-N (random Gaussian jitter per pixel, render_native): at equal
// N the stratified pattern has the lower error on every suite scene tried (docs/tuning.md, stop 34).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "compiler/lir.hpp"

namespace bl::compiler {

// N offsets in pixels, a stratified sample of the pixel filter N(0, sigma_px^2) per axis: point i at
// (Phi^-1((i + 1/2) / N), Phi^-1(frac(radical_inverse_2(i) + 1/(2N)))) sigma_px (Hammersley, through
// the normal quantile). Throws std::invalid_argument for n < 1 or sigma_px not finite and > 0.
std::vector<std::array<float, 2>> supersample_offsets(int n, double sigma_px);

// `plain` (rule none everywhere: InMean inputs only, no sds, gradients or stats) evaluated at each
// offset, outputs averaged; optimized (optimize()). Throws std::invalid_argument when `plain` is not
// plain or `offsets` is empty.
Program supersample(const Program& plain, const std::vector<std::array<float, 2>>& offsets);

// ssN for a sample count: supersample(plain, supersample_offsets(n, sigma_px)), and `plain` itself
// for n = 1 (the footprint-adaptive supersampler's choices, tuner/adaptive_supersampling.hpp).
Program stratified_samples(const Program& plain, int n, double sigma_px);
// One sample of ssN (the plain program at its first offset, input shifts included; `plain` itself
// for n = 1): what the cost model prices n times (CostModel::sequential_cost).
Program one_sample(const Program& plain, int n, double sigma_px);

}  // namespace bl::compiler
