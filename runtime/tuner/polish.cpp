// See polish.hpp.
#include "tuner/polish.hpp"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "compiler/graph_facts.hpp"

namespace bl::tuner {

std::vector<std::pair<int, int>> fused_gene_pairs(const Problem& prob) {
  std::map<int, int> gene_of;  // graph node -> gene
  for (int k = 0; k < prob.space.size(); ++k) gene_of[prob.space.genes[k]] = k;
  std::vector<std::pair<int, int>> out;
  for (const auto& [a, b] : compiler::GraphFacts(*prob.graph).fused_pairs()) {
    const auto ia = gene_of.find(a), ib = gene_of.find(b);
    if (ia == gene_of.end() || ib == gene_of.end() || a == b) continue;
    const std::pair<int, int> p{std::min(ia->second, ib->second), std::max(ia->second, ib->second)};
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  }
  return out;
}

Point polish(const SceneTuner& t, const Point& start, double limit, const PolishOptions& opt) {
  const Problem& prob = t.problem();
  const int rules = static_cast<int>(prob.palette.rules.size());
  const std::vector<std::pair<int, int>> pairs = fused_gene_pairs(prob);
  if (limit < 0) limit = start.obj.error;
  Point cur = start;
  int evals = 0;
  for (int step = 0; step < opt.max_steps && evals < opt.max_evals; ++step) {
    // Model time of every single-gene change and every change of a fused pair to one rule (lowering
    // and the cost model only).
    std::vector<std::pair<double, Genome>> cheaper;
    auto consider = [&](Genome x) {
      const auto p = t.lower(t.schedule(x));
      if (!p) return;
      const double time = t.cost_model().cost(*p);
      if (time < cur.obj.time) cheaper.emplace_back(time, std::move(x));
    };
    for (int g = 0; g < prob.space.size(); ++g)
      for (int r = 0; r < rules; ++r) {
        if (r == cur.genome[g]) continue;
        Genome x = cur.genome;
        x[g] = static_cast<std::uint8_t>(r);
        consider(std::move(x));
      }
    for (const auto& [ga, gb] : pairs)
      for (int r = 0; r < rules; ++r) {
        if (r == cur.genome[ga] || r == cur.genome[gb]) continue;  // single-gene moves cover these
        Genome x = cur.genome;
        x[ga] = x[gb] = static_cast<std::uint8_t>(r);
        consider(std::move(x));
      }
    std::stable_sort(cheaper.begin(), cheaper.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
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
