// The sweep over sigma: worst error over an entry's x values at each sigma, for the emitted and the
// naive form, in double and float.
#pragma once

#include <vector>

#include "entries.hpp"

namespace nbs {

// sigma = 10^(k/4), k = -48..24: 1e-12 to 1e6.
std::vector<double> sigma_grid();

struct Point {
  double sigma;
  double naive_d, emitted_d, naive_f, emitted_f;  // +inf: NaN or inf where the reference is finite
  int skipped_f;                                  // x whose reference overflows float (not counted)
};

std::vector<Point> sweep(const Entry& e, const std::vector<double>& sigmas);

}  // namespace nbs
