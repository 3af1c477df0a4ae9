// The median of a sample (NaN when empty): the cost-model benchmarks' accuracy summaries.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace bl::bench {

inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace bl::bench
