// See polish.hpp.
#include "tuner/polish.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ir/atomics.hpp"

namespace bl::tuner {

namespace {

bool is_call(const ir::Graph& g, int n, const char* atomic) {
  return n >= 0 && g.node(n).op == ir::Op::Call && std::string(ir::atomic_name(g.node(n).atomic)) == atomic;
}

// The node a value is an affine function of through constant adds, subtracts and scales (itself
// when it is none of those): the compiler fuses floors of one base, steps of one fract.
int affine_base(const ir::Graph& g, int n) {
  auto cst = [&](int j) { return j >= 0 && g.node(j).op == ir::Op::Const; };
  for (;;) {
    const ir::Node& x = g.node(n);
    const bool affine = x.op == ir::Op::Add || x.op == ir::Op::Sub || x.op == ir::Op::Mul;
    if (affine && cst(x.b) && !cst(x.a)) {
      n = x.a;
    } else if (affine && cst(x.a) && !cst(x.b)) {
      n = x.b;
    } else if (x.op == ir::Op::Neg) {
      n = x.a;
    } else {
      return n;
    }
  }
}

}  // namespace

std::vector<std::pair<int, int>> fused_gene_pairs(const Problem& prob) {
  const ir::Graph& g = *prob.graph;
  std::map<int, int> gene_of;  // graph node -> gene
  for (int k = 0; k < prob.space.size(); ++k) gene_of[prob.space.genes[k]] = k;
  std::vector<std::pair<int, int>> out;
  auto add = [&](int a, int b) {
    const int base = affine_base(g, g.node(a).a);
    if (base != affine_base(g, g.node(b).a)) return;
    if (is_call(g, a, "step") && !is_call(g, base, "fract")) return;  // a window reads one fract
    const auto ia = gene_of.find(a), ib = gene_of.find(b);
    if (ia == gene_of.end() || ib == gene_of.end() || a == b) return;
    const std::pair<int, int> p{std::min(ia->second, ib->second), std::max(ia->second, ib->second)};
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  for (int n = 0; n < g.size(); ++n) {
    const ir::Node& x = g.node(n);
    if (x.op == ir::Op::Sub && is_call(g, x.a, "floor") && is_call(g, x.b, "floor")) add(x.a, x.b);
    if (x.op != ir::Op::Mul) continue;
    if (is_call(g, x.a, "step") && is_call(g, x.b, "step")) add(x.a, x.b);
    // The second pair of a left-to-right product chain, (Q * A) * B.
    for (const auto [inner, other] : {std::pair{x.a, x.b}, std::pair{x.b, x.a}}) {
      if (inner < 0 || g.node(inner).op != ir::Op::Mul || !is_call(g, other, "step")) continue;
      for (int a : {g.node(inner).a, g.node(inner).b})
        if (is_call(g, a, "step")) add(a, other);
    }
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
