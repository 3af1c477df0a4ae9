// Gaussian expectations of a plain function by the midpoint rule: the references of the rule tests
// (an independent computation in double, no lowering).
#pragma once

#include <cmath>

namespace bl::testing {

// E[f(mu + s Z)], Z a standard normal: n points on +-half_width sd.
template <class F>
double gaussian_mean_1d(const F& f, double mu, double s, int n, double half_width = 8) {
  double sum = 0, wsum = 0;
  for (int k = 0; k < n; ++k) {
    const double z = -half_width + (k + 0.5) * 2 * half_width / n;
    const double w = std::exp(-0.5 * z * z);
    sum += w * f(mu + s * z);
    wsum += w;
  }
  return sum / wsum;
}

// E[f(mu + su Z1, mv + sv Z2)], Z1, Z2 independent standard normals: n^2 points on +-6 sd.
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
