// Value ranges of a graph's nodes by interval arithmetic: what a node's plain value can be for any
// value of the inputs. Inputs and textures are unbounded; an atomic's range is the catalog's,
// narrowed to the image of its argument's interval where the atomic is monotone on each side of 0
// (powers, exp, sqrt, log, abs, saturate, smoothstep, floor, ...). The compiler keeps Dorn's
// heuristic means inside these ranges (a mean of values in [lo, hi] lies in [lo, hi]).
#pragma once

#include <limits>
#include <vector>

#include "ir/graph.hpp"

namespace bl::ir {

struct Interval {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool bounded() const;  // at least one finite end
};

std::vector<Interval> node_ranges(const Graph& g);

}  // namespace bl::ir
