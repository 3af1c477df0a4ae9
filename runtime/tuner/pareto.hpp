// Pareto ranking of (time, error) points, both minimized: non-dominated sorting (Deb et al.'s
// NSGA-II fronts) and the non-dominated subset.
#pragma once

#include <vector>

namespace bl::tuner {

struct Objectives {
  double time = 0;   // ns per pixel (cost model)
  double error = 0;  // RMS in display space
};

// a dominates b: no worse in both, strictly better in one.
bool dominates(const Objectives& a, const Objectives& b);

// Rank per point: 0 for the non-dominated front, 1 for the front of the rest, and so on.
std::vector<int> pareto_ranks(const std::vector<Objectives>& pts);

// Indices of the non-dominated points, sorted by time then error; among exact duplicates only the
// first index is kept.
std::vector<int> pareto_front(const std::vector<Objectives>& pts);

}  // namespace bl::tuner
