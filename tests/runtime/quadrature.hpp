// E[f(mu + su Z1, mv + sv Z2)], Z1, Z2 independent standard normals, by the midpoint rule on +-6 sd
// in each axis (n^2 points): the 2D reference of the rule tests (an independent computation in double
// of the plain function, no lowering).
#pragma once

#include <cmath>

namespace bl::testing {

template <class F>
double gaussian_mean_2d(const F& f, double mu, double mv, double su, double sv, int n = 400) {
  double sum = 0, wsum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double zu = -6 + (i + 0.5) * 12.0 / n, zv = -6 + (j + 0.5) * 12.0 / n;
      const double w = std::exp(-0.5 * (zu * zu + zv * zv));
      sum += w * f(mu + su * zu, mv + sv * zv);
      wsum += w;
    }
  return sum / wsum;
}

}  // namespace bl::testing
