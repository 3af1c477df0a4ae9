// fract under the Gaussian: the measurements of the notebook (errors against the 50-digit
// reference, ns per call), kept apart from the Markdown and the plots.
#pragma once

#include <vector>

namespace nbf {

inline const std::vector<int> kTerms = {1, 2, 4, 8, 16, 32, 64, 128};
inline const std::vector<double> kSigmas = {0.01, 0.02, 0.05, 0.1, 0.2, 0.5};

// Worst |value - reference| / max(1, |reference|) over the x grid at one sigma.
struct Errors {
  double sigma;
  std::vector<double> naive;  // per kTerms: Dorn et al.'s series truncated after K terms
  double ours;                // bl::gaussian::fract, double
  double ours_float;          // bl::gaussian::fract, float (reference at the float inputs)
  double box_vs_gauss;        // bl::box::fract against the Gaussian reference (kernel mismatch)
  double tent_vs_gauss;
  double box_own;  // bl::box::fract against the exact box reference
  double tent_own;
};

struct Timings {
  double sigma;
  std::vector<double> naive;  // ns per call, per kTerms
  double ours, ours_float, box, tent, plain;
};

inline constexpr int kPeriodPoints = 1000;

// The x grid: kPeriodPoints points across a period, the points next to the jump and a few far away.
std::vector<double> error_grid();

Errors measure_errors(double sigma, const std::vector<double>& xs);
Timings measure_timings(double sigma);

// Largest |closed-form reference - tanh_sinh quadrature| at a few (x, sigma); n: how many.
double reference_check(int& n);

}  // namespace nbf
