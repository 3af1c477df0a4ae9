// The paper does not state the mu_X range of its MSEs. MSE over [-R, R] as a function of R (from one
// evaluation on a wide grid), and the R whose MSEs come closest to the printed ones.
#pragma once

#include <vector>

#include "paper_examples.hpp"

namespace nb::clamped {

struct RangeFit {
  std::vector<double> rs;
  std::vector<std::vector<std::vector<double>>> mse;  // [example][method][r index]
  int best = -1;                                      // index into rs
  double best_score = 0;  // RMS over the printed values of log10(ours / paper) at rs[best]
  int printed = 0;        // how many printed values entered the score
};

// `wide`: each example evaluated on a grid symmetric about 0 that covers every R of `rs`.
RangeFit fit_range(const std::vector<clamped_paper::Example>& examples,
                   const std::vector<clamped_paper::Evaluation>& wide, const std::vector<double>& rs);

// The MSE of method m of an example over |mu| <= r, from its wide evaluation.
double mse_within(const clamped_paper::Evaluation& wide, std::size_t m, double r);

}  // namespace nb::clamped
