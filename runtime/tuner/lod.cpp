// See lod.hpp.
#include "tuner/lod.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace bl::tuner {

LodChoice fastest_lod(const std::vector<std::vector<double>>& sq, const std::vector<float>& fp,
                      const std::vector<double>& model_ns, double miss_sq, long pixels, double target,
                      double dispatch_ns, int limits) {
  const auto c = lod_candidates(sq, fp, model_ns, miss_sq, pixels, target, dispatch_ns, limits, 1);
  return c.empty() ? LodChoice() : c.front();
}

std::vector<LodChoice> lod_candidates(const std::vector<std::vector<double>>& sq,
                                      const std::vector<float>& fp, const std::vector<double>& model_ns,
                                      double miss_sq, long pixels, double target, double dispatch_ns,
                                      int limits, int keep) {
  const std::size_t programs = sq.size(), n = fp.size();
  if (model_ns.size() != programs)
    throw std::invalid_argument("lod_candidates: " + std::to_string(programs) + " error rows for " +
                                std::to_string(model_ns.size()) + " model times");
  for (const auto& row : sq)
    if (row.size() != n)
      throw std::invalid_argument("lod_candidates: an error row has " + std::to_string(row.size()) +
                                  " pixels, the footprints " + std::to_string(n));
  if (pixels <= 0 || static_cast<std::size_t>(pixels) < n || limits < 2)
    throw std::invalid_argument("lod_candidates: " + std::to_string(pixels) + " pixels for " +
                                std::to_string(n) + " hit pixels, " + std::to_string(limits) + " limits");
  std::vector<LodChoice> out;
  if (n == 0) return out;
  // Pixels by footprint; prefix sums of each program's errors in that order.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return fp[a] < fp[b]; });
  std::vector<float> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = fp[order[i]];
  std::vector<std::vector<double>> prefix(programs, std::vector<double>(n + 1, 0.0));
  for (std::size_t k = 0; k < programs; ++k)
    for (std::size_t i = 0; i < n; ++i) prefix[k][i + 1] = prefix[k][i] + sq[k][order[i]];
  // Split points: near = the first j pixels, all with a footprint below sorted[j] (ties stay together).
  std::vector<std::size_t> splits;
  for (int q = 1; q < limits; ++q) {
    const std::size_t at = static_cast<std::size_t>(static_cast<double>(q) * n / limits);
    const std::size_t j =
        std::lower_bound(sorted.begin(), sorted.end(), sorted[std::min(at, n - 1)]) - sorted.begin();
    if (j > 0 && j < n && (splits.empty() || splits.back() != j)) splits.push_back(j);
  }
  const double denom = 3.0 * static_cast<double>(pixels);
  for (std::size_t a = 0; a < programs; ++a)
    for (std::size_t b = 0; b < programs; ++b) {
      if (a == b) continue;
      for (std::size_t j : splits) {
        const double share = static_cast<double>(j) / n;
        const double time = share * model_ns[a] + (1 - share) * model_ns[b] + dispatch_ns;
        const double err = std::sqrt((miss_sq + prefix[a][j] + (prefix[b][n] - prefix[b][j])) / denom);
        if (!(err <= target)) continue;
        LodChoice c;
        c.near = static_cast<int>(a);
        c.far = static_cast<int>(b);
        c.limit = sorted[j];
        c.near_share = share;
        c.model_ns = time;
        c.error = err;
        out.push_back(c);
      }
    }
  std::stable_sort(out.begin(), out.end(), [](const LodChoice& x, const LodChoice& y) {
    return x.model_ns < y.model_ns || (x.model_ns == y.model_ns && x.error < y.error);
  });
  if (keep >= 0 && static_cast<int>(out.size()) > keep) out.resize(keep);
  return out;
}

}  // namespace bl::tuner
