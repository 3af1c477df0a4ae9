#include "compiler/periodic_far_field.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <string>
#include <utility>

#include "compiler/graph_facts.hpp"
#include "compiler/plain_eval.hpp"
#include "ir/atomics.hpp"

namespace bl::compiler {
namespace {

bool is_surface_input(const ir::Graph& g, const ir::Node& n) {
  if (n.op != ir::Op::Input) return false;
  const ir::InputDecl& in = g.inputs()[static_cast<std::size_t>(n.value)];
  return in.varying && (in.name == "u" || in.name == "v");
}

// Node j is a constant-coefficient affine function of u and v (and constants).
bool affine_in_surface(const ir::Graph& g, int j, std::vector<signed char>& memo) {
  if (memo[j] >= 0) return memo[j];
  const ir::Node& n = g.node(j);
  auto cst = [&](int k) { return g.node(k).op == ir::Op::Const; };
  bool ok = false;
  switch (n.op) {
    case ir::Op::Const:
      ok = true;
      break;
    case ir::Op::Input:
      ok = is_surface_input(g, n);
      break;
    case ir::Op::Neg:
      ok = affine_in_surface(g, n.a, memo);
      break;
    case ir::Op::Add:
    case ir::Op::Sub:
      ok = affine_in_surface(g, n.a, memo) && affine_in_surface(g, n.b, memo);
      break;
    case ir::Op::Mul:
      ok = (cst(n.a) && affine_in_surface(g, n.b, memo)) || (cst(n.b) && affine_in_surface(g, n.a, memo));
      break;
    case ir::Op::Div:
      ok = cst(n.b) && affine_in_surface(g, n.a, memo);
      break;
    default:
      break;
  }
  return memo[j] = ok;
}

bool is_source(const ir::Graph& g, int j, std::vector<signed char>& affine) {
  const ir::Node& n = g.node(j);
  const bool wraps =
      n.op == ir::Op::Mod || (n.op == ir::Op::Call && std::string(ir::atomic_name(n.atomic)) == "fract");
  return wraps && g.node(n.a).op != ir::Op::Const && affine_in_surface(g, n.a, affine);
}

ProcessMemo<std::pair<std::uint64_t, int>, PeriodicFarField::Moments>& moments_memo() {
  static ProcessMemo<std::pair<std::uint64_t, int>, PeriodicFarField::Moments> memo;
  return memo;
}

}  // namespace

PeriodicFarField::PeriodicFarField(const ir::Graph& g) : g_(g), sources_(g.size()), output_(g.size(), false) {
  std::vector<signed char> affine(g.size(), -1);
  std::vector<bool> bad(g.size(), false);  // reads the surface (or another input) not through a source
  for (int i = 0; i < g.size(); ++i) {
    const ir::Node& n = g.node(i);
    if (n.op == ir::Op::Input || n.op == ir::Op::Texture) {
      bad[i] = true;
      continue;
    }
    if (is_source(g, i, affine)) {
      sources_[i] = {i};
      continue;
    }
    for (int a : {n.a, n.b, n.c}) {
      if (a < 0) continue;
      if (bad[a]) bad[i] = true;
      std::vector<int> merged;
      std::set_union(sources_[i].begin(), sources_[i].end(), sources_[a].begin(), sources_[a].end(),
                     std::back_inserter(merged));
      sources_[i] = std::move(merged);
    }
    if (bad[i]) sources_[i].clear();
  }
  for (int o : g.outputs())
    if (!sources_[o].empty()) output_[o] = true;
}

double PeriodicFarField::period(int j) const {
  const ir::Node& n = g_.node(j);
  return n.op == ir::Op::Mod ? std::fabs(n.value) : 1.0;
}

PeriodicFarField::Moments PeriodicFarField::spatial(int i) const {
  if (sources_[i].empty()) return {};
  if (hash_ == 0) hash_ = g_.hash();
  if (const auto m = moments_memo().find({hash_, i})) return *m;
  std::vector<double> in(g_.inputs().size(), 0.0);
  int su = -1, sv = -1;
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (g_.inputs()[k].name == "u") su = static_cast<int>(k);
    if (g_.inputs()[k].name == "v") sv = static_cast<int>(k);
  }
  auto values = [&](double u, double v) {
    if (su >= 0) in[su] = u;
    if (sv >= 0) in[sv] = v;
    return plain_values(g_, in);
  };
  // Each source's frequency (periods per unit of u, v): its argument is affine, so differences are exact.
  const std::vector<double> x0 = values(0, 0), xu = values(1, 0), xv = values(0, 1);
  double longest = 0;
  Moments out;
  for (int j : sources_[i]) {
    const int a = g_.node(j).a;
    const double f = std::hypot(xu[a] - x0[a], xv[a] - x0[a]) / period(j);
    if (!(f > 0) || !std::isfinite(f)) return moments_memo().put({hash_, i}, out);
    longest = std::max(longest, 1 / f);
  }
  const double side = 32 * longest;
  constexpr int kGrid = 128;
  std::mt19937_64 rng(0x5EEDull + static_cast<std::uint64_t>(i));
  std::uniform_real_distribution<double> U(0, 1);
  double sum = 0, sum2 = 0;
  for (int r = 0; r < kGrid; ++r)
    for (int c = 0; c < kGrid; ++c) {
      const double y = values(side * (c + U(rng)) / kGrid, side * (r + U(rng)) / kGrid)[i];
      if (!std::isfinite(y)) return moments_memo().put({hash_, i}, out);
      sum += y;
      sum2 += y * y;
    }
  out.mean = sum / (kGrid * kGrid);
  out.second = sum2 / (kGrid * kGrid);
  out.ok = true;
  return moments_memo().put({hash_, i}, out);
}

}  // namespace bl::compiler
