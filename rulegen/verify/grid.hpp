// blverify: the (x, sigma) grid every entry is checked on.
#pragma once

#include <string>
#include <vector>

#include "spec.hpp"

namespace blv {

struct GridPoint {
  double x, sigma;
};

// x values: the base grid plus, for each break b (first period), b, b +- 1e-9, b +- 1e-4;
// moments (rule "moment") use a smaller base grid. Sorted, unique; includes points outside the
// domain (the caller checks NaN there for compact entries and skips them otherwise).
std::vector<double> x_grid(const Spec& spec, bool moment);
const std::vector<double>& sigma_grid();
std::vector<GridPoint> grid(const Spec& spec, bool moment);

// Human-readable description for the report.
std::string grid_description();

}  // namespace blv
