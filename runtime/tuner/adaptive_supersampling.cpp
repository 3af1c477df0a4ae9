// See adaptive_supersampling.hpp.
#include "tuner/adaptive_supersampling.hpp"

#include <vector>

#include "compiler/supersample.hpp"
#include "tuner/lod.hpp"
#include "tuner/lod_pricing.hpp"

namespace bl::tuner {

std::optional<AdaptiveSupersampling> adaptive_supersampling(const SceneTuner& t, double target) {
  const auto plain = t.lower_plain();
  if (!plain) return std::nullopt;
  const double sigma_px = t.scene().sigma_px;
  const PixelSample& all = t.full_sample();
  std::vector<int> counts;
  std::vector<compiler::Program> one;  // one sample of each (its input shifts included): its price
  std::vector<std::vector<double>> sq;
  std::vector<double> model_ns;
  for (int n : kAdaptiveSampleCounts) {
    counts.push_back(n);
    one.push_back(compiler::one_sample(*plain, n, sigma_px));
    sq.push_back(all.pixel_sq(compiler::stratified_samples(*plain, n, sigma_px)));
    model_ns.push_back(t.cost_model().sequential_cost(one.back(), n));
  }
  const double dispatch = lod_dispatch_ns(t.cost_model());
  const auto cands =
      lod_candidates(sq, all.footprints(), model_ns, all.miss_sq(), all.count(), target, dispatch, 64, 48);
  const LodChoice c = fastest_on_own_pixels(
      t, cands, [&](const CostModel& m, int k) { return m.sequential_cost(one[k], counts[k]); }, dispatch);
  if (c.near < 0) return std::nullopt;
  AdaptiveSupersampling a;
  a.near_samples = counts[c.near];
  a.far_samples = counts[c.far];
  a.limit = c.limit;
  a.near_share = c.near_share;
  a.model_ns = c.model_ns;
  a.error = c.error;
  return a;
}

}  // namespace bl::tuner
