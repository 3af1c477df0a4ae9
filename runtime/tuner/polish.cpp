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

namespace {

// Every single-gene change of g and every change of a fused pair to one rule, with its model time
// (lowering and the cost model only, no pixels), kept when keep(time).
template <class Keep>
std::vector<std::pair<double, Genome>> moves(const SceneTuner& t, const Genome& g, Keep keep) {
  std::vector<std::pair<double, Genome>> out;
  for (const GeneMove& m :
       gene_moves(t.problem(), fused_gene_pairs(t.problem()), [&](int k, int r) { return g[k] == r; })) {
    Genome x = g;
    x[m.a] = static_cast<std::uint8_t>(m.rule);
    if (m.b >= 0) x[m.b] = static_cast<std::uint8_t>(m.rule);
    const auto p = t.lower(t.schedule(x));
    if (!p) continue;
    const double time = t.cost_model().cost(*p);
    if (keep(time)) out.emplace_back(time, std::move(x));
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

}  // namespace

Point reach(const SceneTuner& t, const Point& start, double target, double budget, const PolishOptions& opt) {
  Point cur = start;
  int evals = 0;
  for (int step = 0; step < opt.max_steps && evals < opt.max_evals && cur.obj.error > target; ++step) {
    const auto cand = moves(t, cur.genome, [&](double time) { return time < budget; });
    Point best = cur;
    bool reached = false;
    for (int k = 0; k < static_cast<int>(cand.size()) && k < opt.max_evals_per_step && evals < opt.max_evals;
         ++k) {
      const Objectives o = t.evaluate(t.schedule(cand[k].second));
      ++evals;
      if (o.error <= target) {  // the cheapest change that reaches the target
        best = Point{cand[k].second, o};
        reached = true;
        break;
      }
      if (o.error < best.obj.error) best = Point{cand[k].second, o};
    }
    if (best.genome == cur.genome) break;
    cur = best;
    if (reached) break;
  }
  return cur;
}

Point polish(const SceneTuner& t, const Point& start, double limit, const PolishOptions& opt) {
  if (limit < 0) limit = start.obj.error;
  Point cur = start;
  int evals = 0;
  for (int step = 0; step < opt.max_steps && evals < opt.max_evals; ++step) {
    const auto cheaper = moves(t, cur.genome, [&](double time) { return time < cur.obj.time; });
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

int cheapest_under(const std::vector<Point>& pts, double limit) {
  int best = -1;
  for (int j = 0; j < static_cast<int>(pts.size()); ++j)
    if (pts[j].obj.error <= limit && (best < 0 || pts[j].obj.time < pts[best].obj.time)) best = j;
  return best;
}

std::vector<Point> uniform_points(const SceneTuner& t) {
  std::vector<Point> out;
  for (int r = 0; r < static_cast<int>(t.problem().palette.rules.size()); ++r) {
    Point u{uniform_genome(t.problem().space, r), {}};
    u.obj = t.evaluate(t.schedule(u.genome));
    out.push_back(std::move(u));
  }
  return out;
}

std::optional<Point> polish_from_uniform(const SceneTuner& t, const std::vector<Point>& uniform, double limit,
                                         const PolishOptions& opt) {
  const int i = cheapest_under(uniform, limit);
  if (i < 0) return std::nullopt;
  return polish(t, uniform[i], limit, opt);
}

}  // namespace bl::tuner
