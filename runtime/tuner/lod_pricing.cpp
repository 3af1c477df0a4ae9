// See lod_pricing.hpp.
#include "tuner/lod_pricing.hpp"

#include <map>
#include <utility>

namespace bl::tuner {

double lod_dispatch_ns(const CostModel& m) {
  double ns = 0;
  for (const char* op : {"max", "less"})
    if (const auto it = m.op_ns.find(op); it != m.op_ns.end()) ns += it->second;
  return ns;
}

LodChoice fastest_on_own_pixels(const SceneTuner& t, const std::vector<LodChoice>& cands,
                                const std::function<double(const CostModel&, int)>& price,
                                double dispatch_ns) {
  std::map<float, std::pair<CostModel, CostModel>> priced;  // by limit: near and far pixels' models
  LodChoice best;
  for (LodChoice k : cands) {
    auto it = priced.find(k.limit);
    if (it == priced.end()) {
      const PixelSample& smp = t.search_sample();
      it = priced
               .emplace(k.limit, std::make_pair(t.cost_model_over(smp.subset(k.limit, true)),
                                                t.cost_model_over(smp.subset(k.limit, false))))
               .first;
    }
    k.model_ns = k.near_share * price(it->second.first, k.near) +
                 (1 - k.near_share) * price(it->second.second, k.far) + dispatch_ns;
    if (best.near < 0 || k.model_ns < best.model_ns) best = k;
  }
  return best;
}

}  // namespace bl::tuner
