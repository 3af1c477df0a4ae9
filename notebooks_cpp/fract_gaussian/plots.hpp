// The two figures of the fract notebook (gnuplot through nb::run_gnuplot).
#pragma once

#include <string>
#include <vector>

#include "measure.hpp"

namespace nbf {

// Terms of the truncated series drawn in the curves figure.
inline const std::vector<int> kCurveTerms = {2, 4, 8, 16};
inline const std::vector<double> kCurveSigmas = {0.02, 0.05, 0.1};

// fract, the truncated series for kCurveTerms, bl::gaussian/box/tent::fract over x in [-1, 2], one
// panel per kCurveSigmas.
void plot_curves(const std::string& png);

// (a) worst error against K per sigma, our form as dashed levels; (b) worst error against ns/call.
void plot_errors(const std::string& png, const std::vector<Errors>& errs, const std::vector<Timings>& times);

}  // namespace nbf
