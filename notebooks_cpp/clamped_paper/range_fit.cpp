// See range_fit.hpp.
#include "range_fit.hpp"

#include <cmath>

namespace nb::clamped {

double mse_within(const clamped_paper::Evaluation& wide, std::size_t m, double r) {
  double se = 0;
  int n = 0;
  for (std::size_t i = 0; i < wide.mu.size(); ++i) {
    if (std::fabs(wide.mu[i]) > r + 1e-9) continue;
    const double e = wide.values[m][i] - wide.truth[i];
    se += e * e;
    ++n;
  }
  return n ? se / n : NAN;
}

RangeFit fit_range(const std::vector<clamped_paper::Example>& examples,
                   const std::vector<clamped_paper::Evaluation>& wide, const std::vector<double>& rs) {
  RangeFit f;
  f.rs = rs;
  f.mse.resize(examples.size());
  for (std::size_t e = 0; e < examples.size(); ++e)
    for (std::size_t m = 0; m < examples[e].methods.size(); ++m) {
      std::vector<double> v;
      for (const double r : rs) v.push_back(mse_within(wide[e], m, r));
      f.mse[e].push_back(v);
    }
  for (std::size_t i = 0; i < rs.size(); ++i) {
    double sq = 0;
    int n = 0;
    for (std::size_t e = 0; e < examples.size(); ++e)
      for (std::size_t m = 0; m < examples[e].methods.size(); ++m) {
        const auto it = examples[e].paper_mse.find(examples[e].methods[m].key);
        if (it == examples[e].paper_mse.end()) continue;
        const double l = std::log10(f.mse[e][m][i] / it->second);
        sq += l * l;
        ++n;
      }
    const double score = std::sqrt(sq / n);
    if (f.best < 0 || score < f.best_score) {
      f.best = static_cast<int>(i);
      f.best_score = score;
      f.printed = n;
    }
  }
  return f;
}

}  // namespace nb::clamped
