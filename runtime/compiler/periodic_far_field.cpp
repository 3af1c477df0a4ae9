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

ProcessMemo<std::pair<std::uint64_t, int>, PeriodicFarField::Axes>& axes_memo() {
  static ProcessMemo<std::pair<std::uint64_t, int>, PeriodicFarField::Axes> memo;
  return memo;
}

// The smallest common multiple of the periods p (each > 0) among k * max(p), k = 1..16, within a
// relative 1e-6; 0 when there is none (incommensurate or too long).
double common_period(const std::vector<double>& p) {
  const double longest = *std::max_element(p.begin(), p.end());
  for (int k = 1; k <= 16; ++k) {
    const double L = k * longest;
    bool all = true;
    for (double q : p) {
      const double r = L / q;
      all = all && std::fabs(r - std::round(r)) <= 1e-6 * r;
    }
    if (all) return L;
  }
  return 0;
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
  // Nodes every path of which to the outputs is +, -, * or / by constants (a mix of two colours by a
  // tiling's mask, per channel): their far field passes to the outputs exactly, so it is taken once
  // at the deepest such node with sources (the mask) instead of at each channel.
  std::vector<bool> affine_out(g.size(), false);
  for (int o : g.outputs()) affine_out[o] = true;
  std::vector<std::vector<int>> readers(g.size());
  for (int i = 0; i < g.size(); ++i)
    for (int a : {g.node(i).a, g.node(i).b, g.node(i).c})
      if (a >= 0) readers[a].push_back(i);
  auto constant_affine = [&](int r, int of) {  // r is of op a constant
    const ir::Node& n = g.node(r);
    auto cst = [&](int j) { return j >= 0 && g.node(j).op == ir::Op::Const; };
    switch (n.op) {
      case ir::Op::Neg:
        return true;
      case ir::Op::Add:
      case ir::Op::Sub:
      case ir::Op::Mul:
        return (n.a == of && cst(n.b)) || (n.b == of && cst(n.a));
      case ir::Op::Div:
        return n.a == of && cst(n.b);
      default:
        return false;
    }
  };
  for (int i = g.size() - 1; i >= 0; --i) {
    if (readers[i].empty()) continue;
    bool all = true;
    for (int r : readers[i]) all = all && affine_out[r] && constant_affine(r, i);
    affine_out[i] = affine_out[i] || all;
  }
  for (int i = 0; i < g.size(); ++i) {
    if (sources_[i].empty() || !affine_out[i]) continue;
    const ir::Node& n = g.node(i);
    bool deepest = true;  // not itself a constant map of a node that qualifies
    for (int a : {n.a, n.b})
      if (a >= 0 && !sources_[a].empty() && affine_out[a] && constant_affine(i, a)) deepest = false;
    output_[i] = deepest;
  }
}

int PeriodicFarField::surface_slot(const char* name) const {
  for (std::size_t k = 0; k < g_.inputs().size(); ++k)
    if (g_.inputs()[k].name == name) return static_cast<int>(k);
  return -1;
}

std::pair<double, double> PeriodicFarField::argument_slope(int j) const {
  if (at00_.empty()) {  // the argument is affine, so differences of plain values are exact
    at00_ = plain_at_surface(g_, 0, 0);
    at10_ = plain_at_surface(g_, 1, 0);
    at01_ = plain_at_surface(g_, 0, 1);
  }
  const int a = g_.node(j).a;
  return {at10_[a] - at00_[a], at01_[a] - at00_[a]};
}

double PeriodicFarField::period(int j) const {
  const ir::Node& n = g_.node(j);
  return n.op == ir::Op::Mod ? std::fabs(n.value) : 1.0;
}

PeriodicFarField::Moments PeriodicFarField::spatial(int i) const {
  if (sources_[i].empty()) return {};
  if (hash_ == 0) hash_ = g_.hash();
  if (const auto m = moments_memo().find({hash_, i})) return *m;
  // Each source's frequency (periods per unit of u, v).
  double longest = 0;
  Moments out;
  for (int j : sources_[i]) {
    const auto [du, dv] = argument_slope(j);
    const double f = std::hypot(du, dv) / period(j);
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
      const double y = plain_at_surface(g_, side * (c + U(rng)) / kGrid, side * (r + U(rng)) / kGrid)[i];
      if (!std::isfinite(y)) return moments_memo().put({hash_, i}, out);
      sum += y;
      sum2 += y * y;
    }
  out.mean = sum / (kGrid * kGrid);
  out.second = sum2 / (kGrid * kGrid);
  out.ok = true;
  return moments_memo().put({hash_, i}, out);
}

PeriodicFarField::Axes PeriodicFarField::axes(int i) const {
  if (sources_[i].empty()) return {};
  if (hash_ == 0) hash_ = g_.hash();
  if (const auto m = axes_memo().find({hash_, i})) return *m;
  Axes out;
  const int slot[2] = {surface_slot("u"), surface_slot("v")};
  // Each source reads one axis: its period along that axis, in units of u or v.
  std::vector<double> periods[2];
  for (int j : sources_[i]) {
    const auto [du, dv] = argument_slope(j);
    if (du != 0 && dv != 0) return axes_memo().put({hash_, i}, out);  // a rotated or sheared source
    const int axis = du != 0 ? 0 : 1;
    const double d = axis == 0 ? du : dv;
    if (!(std::isfinite(d) && d != 0)) return axes_memo().put({hash_, i}, out);
    periods[axis].push_back(period(j) / std::fabs(d));
  }
  double L[2] = {0, 0};
  for (int axis = 0; axis < 2; ++axis) {
    if (periods[axis].empty()) continue;
    L[axis] = common_period(periods[axis]);
    if (!(L[axis] > 0)) return axes_memo().put({hash_, i}, out);
  }
  constexpr int kAlong = 1024, kAcross = 128;
  for (int axis = 0; axis < 2; ++axis) {
    Series& s = axis == 0 ? out.u : out.v;
    if (L[axis] == 0) continue;  // constant along this axis
    s.input = slot[axis];
    s.period = L[axis];
    const double across = L[1 - axis];  // 0: constant across, one sample
    const int n_across = across > 0 ? kAcross : 1;
    std::vector<double> F(kAlong);
    for (int p = 0; p < kAlong; ++p) {
      const double x = L[axis] * (p + 0.5) / kAlong;
      double sum = 0;
      for (int q = 0; q < n_across; ++q) {
        const double y = across * (q + 0.5) / n_across;
        const double f = (axis == 0 ? plain_at_surface(g_, x, y) : plain_at_surface(g_, y, x))[i];
        if (!std::isfinite(f)) return axes_memo().put({hash_, i}, Axes{});
        sum += f;
      }
      F[p] = sum / n_across;
    }
    for (double f : F) s.a0 += f / kAlong;
    for (int m = 1; m <= kSeriesTerms; ++m) {
      double a = 0, b = 0;
      for (int p = 0; p < kAlong; ++p) {
        const double t = 2 * M_PI * m * (p + 0.5) / kAlong;
        a += F[p] * std::cos(t);
        b += F[p] * std::sin(t);
      }
      s.a.push_back(2 * a / kAlong);
      s.b.push_back(2 * b / kAlong);
    }
    while (!s.a.empty() && std::fabs(s.a.back()) < kSeriesFloor && std::fabs(s.b.back()) < kSeriesFloor) {
      s.a.pop_back();
      s.b.pop_back();
    }
  }
  out.ok = true;
  return axes_memo().put({hash_, i}, out);
}

}  // namespace bl::compiler
