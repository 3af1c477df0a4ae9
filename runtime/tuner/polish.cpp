// See polish.hpp.
#include "tuner/polish.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace bl::tuner {

Point polish(const SceneTuner& t, const Point& start, double limit, const PolishOptions& opt) {
  const Problem& prob = t.problem();
  const int rules = static_cast<int>(prob.palette.rules.size());
  if (limit < 0) limit = start.obj.error;
  Point cur = start;
  int evals = 0;
  for (int step = 0; step < opt.max_steps && evals < opt.max_evals; ++step) {
    // Model time of every single-gene change (lowering and the cost model only).
    std::vector<std::pair<double, Genome>> cheaper;
    for (int g = 0; g < prob.space.size(); ++g)
      for (int r = 0; r < rules; ++r) {
        if (r == cur.genome[g]) continue;
        Genome x = cur.genome;
        x[g] = static_cast<std::uint8_t>(r);
        const auto p = t.lower(t.schedule(x));
        if (!p) continue;
        const double time = t.cost_model().cost(*p);
        if (time < cur.obj.time) cheaper.emplace_back(time, std::move(x));
      }
    std::sort(cheaper.begin(), cheaper.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    bool moved = false;
    for (int k = 0;
         k < static_cast<int>(cheaper.size()) && k < opt.max_evals_per_step && evals < opt.max_evals; ++k) {
      const Objectives o = t.evaluate(t.schedule(cheaper[k].second));
      ++evals;
      if (o.error <= limit && o.time < cur.obj.time) {
        cur.genome = cheaper[k].second;
        cur.obj = o;
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  return cur;
}

}  // namespace bl::tuner
