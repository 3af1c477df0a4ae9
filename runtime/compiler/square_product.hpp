// Where two square waves of one variable are both 1: the product square(t) * square(n t + d) (square
// = 1 on fract in [0, 1/2)) for an integer frequency ratio n is again an indicator, periodic in t with
// period 1, of a union of intervals. Its Gaussian expectation is then exact through fract's:
// E[1{fract(X) in [a, b)}] = (b - a) - E[fract(X - a)] + E[fract(X - b)] (the pulse is
// floor(X - a) - floor(X - b)). Zigzag's band and hue (square(2y), square(y / 2)) are such a pair;
// Stein's covariance of two jumps at one place is phi^2 where the truth is Phi (1 - Phi).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace bl::compiler {

// The maximal intervals [a, b) of [0, 1) where square(t) = square(n t + d) = 1; n != 0.
inline std::vector<std::pair<double, double>> square_product_intervals(int n, double d) {
  std::vector<double> cut = {0.0, 0.5, 1.0};
  // n t + d crosses a multiple of 1/2 at t = (j / 2 - d) / n.
  const double lo = std::min(d, n + d), hi = std::max(d, n + d);
  for (long j = static_cast<long>(std::floor(2 * lo)) - 1; j <= static_cast<long>(std::ceil(2 * hi)) + 1;
       ++j) {
    const double t = (0.5 * j - d) / n;
    if (t > 0 && t < 1) cut.push_back(t);
  }
  std::sort(cut.begin(), cut.end());
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i + 1 < cut.size(); ++i) {
    const double a = cut[i], b = cut[i + 1];
    if (!(b > a)) continue;
    const double m = 0.5 * (a + b), f = n * m + d;
    if (!(m - std::floor(m) < 0.5 && f - std::floor(f) < 0.5)) continue;
    if (!out.empty() && out.back().second == a)
      out.back().second = b;
    else
      out.push_back({a, b});
  }
  return out;
}

}  // namespace bl::compiler
