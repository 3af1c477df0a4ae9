// Facts about a traced graph that the lowering's rules read, independent of the schedule: who
// reads each node, each node as an affine function of a base, the node each value is a function of
// alone (its root), the lattice nodes (functions of floor/ceil values only), and two continuity
// probes (fract before a wrap-continuous consumer; floors whose jumps the outputs hide).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "compiler/plain_eval.hpp"
#include "ir/atomics.hpp"
#include "ir/graph.hpp"

namespace bl::compiler {

// The process-wide memo tables of GraphFacts (continuity probes, lattice moments) serve the tuner's
// thousands of lowerings of one graph. An embedding that compiles shader after shader would grow
// them without end, so each is emptied when it holds this many entries (results never depend on
// them, only the time to lower). Settable for tests.
inline std::size_t& process_memo_limit() {
  static std::size_t limit = 1u << 14;
  return limit;
}

// A process-wide memo table, keyed by the graph's hash: thread-safe, emptied when it reaches
// process_memo_limit() entries.
template <class Key, class Value>
class ProcessMemo {
 public:
  std::optional<Value> find(const Key& k) {
    std::lock_guard<std::mutex> lock(m_);
    const auto it = map_.find(k);
    return it == map_.end() ? std::nullopt : std::optional<Value>(it->second);
  }
  Value put(const Key& k, const Value& v) {
    std::lock_guard<std::mutex> lock(m_);
    if (map_.size() >= process_memo_limit()) map_.clear();
    return map_[k] = v;
  }
  std::size_t size() {
    std::lock_guard<std::mutex> lock(m_);
    return map_.size();
  }

 private:
  std::map<Key, Value> map_;
  std::mutex m_;
};

class GraphFacts {
 public:
  // Entries in the two process-wide memo tables (for tests of their bound).
  static std::size_t process_memo_entries() { return probe_memo().size() + moment_memo().size(); }

  explicit GraphFacts(const ir::Graph& graph) : g(graph), consumers(graph.size()) {
    for (int i = 0; i < g.size(); ++i)
      for (int a : {g.node(i).a, g.node(i).b, g.node(i).c})
        if (a >= 0) consumers[a].push_back(i);
    for (int o : g.outputs()) consumers[o].push_back(-1);  // an output is a consumer of its own
    aff.resize(g.size());
    root.resize(g.size());
    for (int i = 0; i < g.size(); ++i) {
      aff[i] = affine_form(i);
      root[i] = root_of(i);
    }
    lattice.resize(g.size());
    for (int i = 0; i < g.size(); ++i) lattice[i] = lattice_sources(i);
  }

  // ---- fract whose consumers do not see its jump ----
  // True when every path from node i passes through unary steps (atomics, constant affine maps,
  // x*x) to a value that is the same for fract = 0 and fract = 1, e.g. pow2(fract(x) - 0.5): the
  // composite is continuous at fract's jumps, so fract may report the side of the jump that holds
  // most of the kernel instead of the average of both sides (whose large variance would blur every
  // later step: the grey grid lines of all-Gaussian circles).
  bool wrap_continuous(int i) const {
    double lo = 0, hi = 1;
    int cur = i;
    for (int depth = 0; depth < 32; ++depth) {
      if (consumers[cur].size() != 1 || consumers[cur][0] < 0) return false;
      const int nx = consumers[cur][0];
      const ir::Node& n = g.node(nx);
      const bool a_is = n.a == cur, b_is = n.b == cur;
      auto constant = [&](int j, double* c) {
        if (j < 0 || g.node(j).op != ir::Op::Const) return false;
        *c = g.node(j).value;
        return true;
      };
      double c = 0;
      auto apply = [&](auto fn) {
        lo = fn(lo);
        hi = fn(hi);
      };
      switch (n.op) {
        case ir::Op::Call:
          apply([&](double x) { return ir::plain_atomic(n.atomic, x); });
          break;
        case ir::Op::Neg:
          apply([](double x) { return -x; });
          break;
        case ir::Op::Add:
          if (a_is && b_is)
            apply([](double x) { return 2 * x; });
          else if (!constant(a_is ? n.b : n.a, &c))
            return false;
          else
            apply([&](double x) { return x + c; });
          break;
        case ir::Op::Sub:
          if (a_is && b_is) return false;  // x - x: constant, handled by identical_operands
          if (!constant(a_is ? n.b : n.a, &c)) return false;
          apply([&](double x) { return a_is ? x - c : c - x; });
          break;
        case ir::Op::Mul:
          if (a_is && b_is)
            apply([](double x) { return x * x; });
          else if (!constant(a_is ? n.b : n.a, &c))
            return false;
          else
            apply([&](double x) { return x * c; });
          break;
        default:
          return false;
      }
      if (!std::isfinite(lo) || !std::isfinite(hi)) return false;
      if (std::fabs(lo - hi) <= 1e-9 * std::max(1.0, std::fabs(lo))) return true;
      cur = nx;
    }
    return false;
  }

  // ---- floors whose jumps the output does not show ----
  // The plain graph's outputs in double at surface point (u, v) (plain_at_surface).
  std::vector<double> plain_graph(double u, double v, std::vector<double>* all = nullptr) const {
    const std::vector<double> x = plain_at_surface(g, u, v);  // textures: NaN (no probe)
    std::vector<double> out;
    for (int o : g.outputs()) out.push_back(x[o]);
    if (all) *all = x;
    return out;
  }

  // True when the outputs are continuous where floor(a) jumps: at 6 fixed surface points, walk u
  // (or v, if a does not change with u) until floor(a) changes, bisect the jump to 1e-10 and
  // compare the outputs on both sides (1e-4). Value noise and Truchet tiles are continuous across
  // their cells' edges (a hash of the cell is hidden by the blend or the mortar there);
  // checkerboard's floor(u + 0.5) - floor(u) is not.
  // With a period P != 1 the jumps are those of floor(a / P): a mod(a, P)'s (GLSL's mod(p, s) - s / 2
  // of a hexagonal or rectangular tiling, whose consumers see |.| or a squared length, continuous).
  bool cell_continuous(int a, double period = 1) const {
    const std::pair<int, double> key{a, period};
    auto it = cell_cont.find(key);
    if (it != cell_cont.end()) return it->second;
    // Also cached for the process (each lowering builds its own facts; the probes walk the graph
    // thousands of times). Period 1 keys on the graph's hash alone, another period mixes it in.
    std::uint64_t period_bits = 0;
    if (period != 1) std::memcpy(&period_bits, &period, sizeof period);
    const std::pair<std::uint64_t, int> memo_key{graph_hash() ^ (period_bits * 0x9E3779B97F4A7C15ull), a};
    if (const auto p = probe_memo().find(memo_key)) return cell_cont[key] = *p;
    bool ok = true;
    int probes = 0;
    std::mt19937_64 rng(0xC0FFEEull + static_cast<std::uint64_t>(a));
    std::uniform_real_distribution<double> U(-4, 4);
    for (int t = 0; t < 6 && ok; ++t) {
      const double u0 = U(rng), v0 = U(rng);
      for (int axis = 0; axis < 2 && ok; ++axis) {
        auto at = [&](double w) {
          std::vector<double> all;
          const auto out = axis == 0 ? plain_graph(w, v0, &all) : plain_graph(u0, w, &all);
          return std::make_pair(std::floor(all[a] / period), out);
        };
        const double w0 = axis == 0 ? u0 : v0;
        const double f0 = at(w0).first;
        if (!std::isfinite(f0)) {
          ok = false;
          break;
        }
        double lo = w0, hi = w0;
        bool found = false;
        for (int step = 1; step <= 400 && !found; ++step) {
          hi = w0 + 0.01 * step;
          if (at(hi).first != f0)
            found = true;
          else
            lo = hi;
        }
        if (!found) continue;  // a does not change along this axis here
        for (int b = 0; b < 60 && hi - lo > 1e-10; ++b) {
          const double mid = 0.5 * (lo + hi);
          (at(mid).first == f0 ? lo : hi) = mid;
        }
        const auto L = at(lo).second, R = at(hi).second;
        for (std::size_t c = 0; c < L.size(); ++c)
          if (!(std::fabs(L[c] - R[c]) <= 1e-4)) ok = false;
        ++probes;
        break;  // one jump per probe point
      }
    }
    return cell_cont[key] = probe_memo().put(memo_key, ok && probes >= 3);
  }

  // Node i as (base, n) with i = base^n: pow<n> atomics and products of powers of one base.
  std::pair<int, int> monomial(int i) const {
    const ir::Node& n = g.node(i);
    if (n.op == ir::Op::Call) {
      const std::string f = ir::atomic_name(n.atomic);
      if (f.size() == 4 && f.compare(0, 3, "pow") == 0 && f[3] >= '2' && f[3] <= '8') {
        const std::pair<int, int> c = monomial(n.a);
        return {c.first, c.second * (f[3] - '0')};
      }
    }
    if (n.op == ir::Op::Mul) {
      const std::pair<int, int> a = monomial(n.a), b = monomial(n.b);
      if (a.first == b.first) return {a.first, a.second + b.second};
    }
    return {i, 1};
  }

  // ---- correlation of operands that are functions of one common node ----
  // Node i as alpha + beta * base (base -1: the constant alpha), through constant affine steps.
  struct Affine {
    int base = -1;
    double alpha = 0, beta = 0;
  };

  Affine affine_form(int i) const {
    const ir::Node& n = g.node(i);
    auto cst = [&](int j) { return j >= 0 && g.node(j).op == ir::Op::Const; };
    const Affine self{i, 0, 1};
    switch (n.op) {
      case ir::Op::Const:
        return Affine{-1, n.value, 0};
      case ir::Op::Neg:
        return Affine{aff[n.a].base, -aff[n.a].alpha, -aff[n.a].beta};
      case ir::Op::Add:
      case ir::Op::Sub: {
        const Affine &a = aff[n.a], &b = aff[n.b];
        const double sg = n.op == ir::Op::Add ? 1 : -1;
        if (a.base == b.base || a.base < 0 || b.base < 0)
          return Affine{a.base >= 0 ? a.base : b.base, a.alpha + sg * b.alpha, a.beta + sg * b.beta};
        return self;
      }
      case ir::Op::Mul:
        if (cst(n.b))
          return Affine{aff[n.a].base, aff[n.a].alpha * g.node(n.b).value, aff[n.a].beta * g.node(n.b).value};
        if (cst(n.a))
          return Affine{aff[n.b].base, aff[n.b].alpha * g.node(n.a).value, aff[n.b].beta * g.node(n.a).value};
        return self;
      case ir::Op::Div:
        if (cst(n.b))
          return Affine{aff[n.a].base, aff[n.a].alpha / g.node(n.b).value, aff[n.a].beta / g.node(n.b).value};
        return self;
      default:
        return self;
    }
  }

  // The node a value is a function of alone (its root): through constant affine steps to the base,
  // through atomics to the argument.
  int root_of(int i) const {
    const ir::Node& n = g.node(i);
    if (aff[i].base >= 0 && aff[i].base != i) return root[aff[i].base];
    if (n.op == ir::Op::Call) return root[n.a];
    return i;
  }

  // ---- pairs of nodes the lowering smooths as one function of their common argument ----
  // The structure only: the lowering also asks both nodes for one smoothing kernel at one width and
  // a random argument, and the tuner's polish moves each pair to one rule together.
  bool is_call(int j, const char* atomic) const {
    return j >= 0 && g.node(j).op == ir::Op::Call && std::string(ir::atomic_name(g.node(j).atomic)) == atomic;
  }

  // floor(y + 1/2) - floor(y) at Sub node i (sign +1: 1 where fract(y) >= 1/2), or its negation
  // floor(y) - floor(y + 1/2) (sign -1); `lower` is the floor of y, `upper` that of y + 1/2.
  struct FloorPulse {
    int lower = -1, upper = -1, sign = 0;
  };
  std::optional<FloorPulse> floor_pulse(int i) const {
    const ir::Node& n = g.node(i);
    if (n.op != ir::Op::Sub || !is_call(n.a, "floor") || !is_call(n.b, "floor")) return std::nullopt;
    const Affine &ya = aff[g.node(n.a).a], &yb = aff[g.node(n.b).a];
    if (ya.base < 0 || ya.base != yb.base || ya.beta != yb.beta) return std::nullopt;
    const double d = ya.alpha - yb.alpha;
    if (d != 0.5 && d != -0.5) return std::nullopt;
    return d > 0 ? FloorPulse{n.b, n.a, 1} : FloorPulse{n.a, n.b, -1};
  }

  // step(fract(y) - lo) * step(hi - fract(y)), 0 < lo < hi < 1, either order, at Mul node i: the two
  // steps, the fract, and `other` the remaining factor when the pair is the tail of a product chain
  // ((other * a) * b; -1 when the node is the pair's own product). The direct pair first, then the
  // chain's, in a fixed order.
  struct FractWindow {
    int a = -1, b = -1, other = -1, fract = -1;
    double lo = 0, hi = 0;
  };
  std::vector<FractWindow> fract_windows(int i) const {
    std::vector<FractWindow> out;
    const ir::Node& n = g.node(i);
    if (n.op != ir::Op::Mul) return out;
    auto pair = [&](int ja, int jb, int other) {
      int fa = -1, fb = -1, da = 0, db = 0;
      double ca = 0, cb = 0;
      auto edge = [&](int j, int* fract, double* c, int* dir) {  // a step at a constant edge of a fract
        if (!is_call(j, "step")) return false;
        const auto fs = fract_step(j);
        if (!fs || fs->edge >= 0 || fs->period != 1) return false;
        *fract = fs->fract;
        *c = fs->c;
        *dir = fs->dir;
        return true;
      };
      if (!edge(ja, &fa, &ca, &da) || !edge(jb, &fb, &cb, &db) || fa != fb || da == db) return;
      const double lo = da > 0 ? ca : cb, hi = da > 0 ? cb : ca;
      if (0 < lo && lo < hi && hi < 1) out.push_back({ja, jb, other, fa, lo, hi});
    };
    pair(n.a, n.b, -1);
    for (const auto [inner, last] : {std::pair{n.a, n.b}, std::pair{n.b, n.a}}) {
      if (g.node(inner).op != ir::Op::Mul) continue;
      const ir::Node& m = g.node(inner);
      for (const auto [q, a] : {std::pair{m.a, m.b}, std::pair{m.b, m.a}}) pair(a, last, q);
    }
    return out;
  }

  // step(fract(y) - c) (dir +1: 1 where fract(y) >= c) or step(c - fract(y)) (dir -1) at Step node i,
  // or less(c, fract(y)) (+1) and less(fract(y), c) (-1) at Less node i: a stripe's or a grid line's
  // edge (GLSL step(c, fract(y)), step(fract(y), c), fract(y) < c). The edge c is
  // a constant in (0, 1) (edge -1) or node `edge` (a duty cycle that varies over the surface; the
  // lowering asks its range to lie in [0, 1]).
  struct FractStep {
    int fract = -1, dir = 0, edge = -1;
    double c = 0;
    double period = 1;  // `fract` is mod(x, period) = period fract(x / period) (constant edges only)
  };
  std::optional<FractStep> fract_step(int i) const {
    const ir::Node& n = g.node(i);
    if (n.op == ir::Op::Less) {  // less(fract(y), c): dir -1; less(c, fract(y)): dir +1
      auto edge = [&](int j, int fract, int dir) -> std::optional<FractStep> {
        if (j == fract) return std::nullopt;
        if (g.node(j).op != ir::Op::Const) return FractStep{fract, dir, j, 0};
        const double c = g.node(j).value;
        if (!(0 < c && c < 1)) return std::nullopt;
        return FractStep{fract, dir, -1, c};
      };
      if (is_call(n.a, "fract")) return edge(n.b, n.a, -1);
      if (is_call(n.b, "fract")) return edge(n.a, n.b, 1);
      return std::nullopt;
    }
    if (!is_call(i, "step")) return std::nullopt;
    const int arg = g.node(i).a;
    const Affine& e = aff[arg];
    if (e.base >= 0 && e.beta != 0 && is_call(e.base, "fract")) {
      const double c = -e.alpha / e.beta;  // beta fract + alpha >= 0: fract >= c (beta > 0) or <= c (< 0)
      if (!(0 < c && c < 1)) return std::nullopt;
      return FractStep{e.base, e.beta > 0 ? 1 : -1, -1, c};
    }
    if (e.base >= 0 && e.beta != 0 && g.node(e.base).op == ir::Op::Mod && g.node(e.base).value != 0) {
      const double P = g.node(e.base).value, c = -e.alpha / (e.beta * P);  // on fract(x / P)
      if (!(0 < c && c < 1)) return std::nullopt;
      return FractStep{e.base, e.beta * P > 0 ? 1 : -1, -1, c, P};
    }
    const ir::Node& d = g.node(arg);
    if (d.op != ir::Op::Sub || d.a == d.b) return std::nullopt;
    if (is_call(d.a, "fract") && g.node(d.b).op != ir::Op::Const) return FractStep{d.a, 1, d.b, 0};
    if (is_call(d.b, "fract") && g.node(d.a).op != ir::Op::Const) return FractStep{d.b, -1, d.a, 0};
    return std::nullopt;
  }

  // Every such pair of the graph (floor pulses and fract windows), by node, in node order.
  std::vector<std::pair<int, int>> fused_pairs() const {
    std::vector<std::pair<int, int>> out;
    for (int i = 0; i < g.size(); ++i) {
      if (const auto fp = floor_pulse(i)) out.emplace_back(fp->lower, fp->upper);
      for (const FractWindow& w : fract_windows(i)) out.emplace_back(w.a, w.b);
    }
    return out;
  }

  // ---- integer-valued nodes as small discrete distributions ----
  // floor and ceil of N(m, s^2) take the values K-1, K, K+1 (K = floor(m), ceil(m)) with Gaussian
  // interval probabilities (mass beyond them is dropped and the rest renormalised: exact to
  // Phi(-1/s) for s < 1/4). A node computed from at most two such nodes (of different roots) and constants (a
  // lattice hash) is then an exact finite mixture over their <= 9 value pairs: the plain sub-DAG evaluated
  // per pair, weighted. Smoothed as one value instead, the hash of a cell index collapses to 1/2.
  struct Lattice {
    bool ok = false;
    std::vector<int> src;  // the floor/ceil nodes it depends on (sorted)
  };

  bool integer_source(int i) const {
    const ir::Node& n = g.node(i);
    if (n.op != ir::Op::Call) return false;
    const std::string f = ir::atomic_name(n.atomic);
    return f == "floor" || f == "ceil";
  }

  Lattice lattice_sources(int i) const { return lattice_sources_from(i, lattice); }
  // The same over other facts for node i's arguments (lat: a mixture branch's, lower.cpp).
  Lattice lattice_sources_from(int i, const std::vector<Lattice>& lat) const {
    const ir::Node& n = g.node(i);
    if (n.op == ir::Op::Const) return Lattice{true, {}};
    if (integer_source(i)) return Lattice{true, {i}};
    if (n.op == ir::Op::Input || n.op == ir::Op::Texture) return Lattice{};
    Lattice out{true, {}};
    for (int a : {n.a, n.b, n.c}) {
      if (a < 0) continue;
      if (!lat[a].ok) return Lattice{};
      for (int d : lat[a].src)
        if (std::find(out.src.begin(), out.src.end(), d) == out.src.end()) out.src.push_back(d);
    }
    std::sort(out.src.begin(), out.src.end());
    if (out.src.size() > 2) return Lattice{};
    // The mixture weighs value pairs by the product of their probabilities: the two sources must be
    // functions of different roots (floor(u) and floor(v)); floor(u + 1/2) and floor(u) are not
    // independent (checkerboard), and are left to the Gaussian rules.
    if (out.src.size() == 2 && root[g.node(out.src[0]).a] == root[g.node(out.src[1]).a]) return Lattice{};
    return out;
  }

  // The mean and variance of lattice node i's value over the whole lattice: its plain sub-DAG in
  // double with the sources at the 1024 integers (one source) or the 32 x 32 integer pairs (two) from
  // 0 and from 1e4 on. ok only where the two regions agree (the means within a quarter of the spread,
  // the variances within 2x): a hash of the cell, not the cell index itself, whose mean over the
  // lattice does not exist. The points are fixed and the pair grid symmetric, so two traces of one
  // shader numbered differently get the same moments.
  struct LatticeMoments {
    bool ok = false;
    double mean = 0, var = 0;
  };
  // fixed: the comparisons a mixture branch (lower.cpp) fixes, empty outside one; lat: the lattice
  // facts there (`lattice` outside one).
  LatticeMoments lattice_moments(int i, const std::map<int, int>& fixed,
                                 const std::vector<Lattice>& lat) const {
    const std::vector<int>& src = lat.at(i).src;
    LatticeMoments out;
    if (!lat[i].ok || src.empty()) return out;
    // The sub-DAG from the sources to i, in node order.
    std::vector<bool> need(g.size(), false);
    need[i] = true;
    for (int x = i; x >= 0; --x) {
      if (!need[x] || std::find(src.begin(), src.end(), x) != src.end() || fixed.count(x)) continue;
      const ir::Node& n = g.node(x);
      if (const int p = passed(n, fixed); p >= 0) {
        need[p] = true;
        continue;
      }
      for (int a : {n.a, n.b, n.c})
        if (a >= 0) need[a] = true;
    }
    // Cached for the process per graph, node and the fixed comparisons its sub-DAG meets: every
    // lowering (the tuner's thousands) of every mixture branch asks again.
    MomentKey key{graph_hash(), i, {}};
    std::vector<int> order;  // the sub-DAG's nodes, in node order
    for (int x = 0; x <= i; ++x) {
      if (!need[x]) continue;
      order.push_back(x);
      const ir::Node& n = g.node(x);
      if (fixed.count(x)) std::get<2>(key).emplace_back(x, fixed.at(x));
      if (passed(n, fixed) >= 0) std::get<2>(key).emplace_back(n.a, fixed.at(n.a));
    }
    if (const auto hit = moment_memo().find(key)) return *hit;
    std::vector<double> val(g.size(), 0);
    const int count = 1024;
    double mean[2] = {0, 0}, var[2] = {0, 0};
    for (int region = 0; region < 2; ++region) {
      const double base = region ? 10000 : 0;
      double s1 = 0, s2 = 0;
      for (int t = 0; t < count; ++t) {
        for (int x : order) {
          const ir::Node& n = g.node(x);
          const auto at = std::find(src.begin(), src.end(), x);
          if (at != src.end()) {
            val[x] = src.size() == 1 ? base + t : base + (at == src.begin() ? t % 32 : t / 32);
            continue;
          }
          if (const auto f = fixed.find(x); f != fixed.end()) {
            val[x] = f->second;
            continue;
          }
          if (const int p = passed(n, fixed); p >= 0) {
            val[x] = val[p];
            continue;
          }
          const double a = n.a >= 0 ? val[n.a] : 0, b = n.b >= 0 ? val[n.b] : 0, c = n.c >= 0 ? val[n.c] : 0;
          if (!plain_node(n, a, b, c, &val[x])) return out;  // an input: not a lattice function after all
        }
        if (!std::isfinite(val[i])) return out;
        s1 += val[i];
        s2 += val[i] * val[i];
      }
      mean[region] = s1 / count;
      var[region] = std::max(0.0, s2 / count - mean[region] * mean[region]);
    }
    const double spread = std::sqrt(std::max(var[0], var[1]));
    const bool same_var = std::min(var[0], var[1]) * 2 >= std::max(var[0], var[1]);
    out.ok = spread > 0 && same_var && std::fabs(mean[0] - mean[1]) <= 0.25 * spread;
    out.mean = 0.5 * (mean[0] + mean[1]);
    out.var = 0.5 * (var[0] + var[1]);
    return moment_memo().put(key, out);
  }
  // The argument a select passes on when a mixture branch fixes its condition, else -1.
  static int passed(const ir::Node& n, const std::map<int, int>& fixed) {
    if (n.op != ir::Op::Select) return -1;
    const auto f = fixed.find(n.a);
    return f == fixed.end() ? -1 : f->second ? n.b : n.c;
  }

  // A lattice node (not a source) that some non-lattice node or an output reads.
  bool lattice_boundary(int i) const { return lattice_boundary_in(i, lattice); }
  bool lattice_boundary_in(int i, const std::vector<Lattice>& lat) const {
    if (!lat[i].ok || lat[i].src.empty() || integer_source(i)) return false;
    for (int c : consumers[i])
      if (c < 0 || !lat[c].ok) return true;
    return false;
  }

  // ---- Bernoulli comparisons (selects of branches) ----
  // A less node that some select reads as its condition: the select picks one of two lobes, which
  // the mixture rule (lower.cpp, bernoulli_mixture) keeps apart instead of averaging them.
  bool select_condition(int i) const { return g.node(i).op == ir::Op::Less && selects_reading(i) > 0; }

  // ---- Select cascades (last writer wins) ----
  // `if (c) x = A;` traced in a loop or in sequence gives s_n = select(c_n, A_n, s_{n-1}), ...,
  // s_1 = select(c_1, A_1, x0): the value is the A of the last condition that holds. A link is a
  // condition and the value of it that passes x on to the link below (0: the select's else side; 1
  // when the chain continues through the then side, as `if (!c) ... else x = A` traces).
  struct Link {
    int cond;
    int pass;
  };
  // The cascade from select s down, top first; is_cond says which conditions qualify (the Bernoulli
  // ones). A condition met twice ends it (the two links would not be independent outcomes).
  template <class Pred>
  std::vector<Link> cascade(int s, const Pred& is_cond) const {
    std::vector<Link> out;
    auto link_at = [&](int j) { return j >= 0 && g.node(j).op == ir::Op::Select && is_cond(g.node(j).a); };
    while (link_at(s)) {
      const ir::Node& n = g.node(s);
      for (const Link& l : out)
        if (l.cond == n.a) return out;
      const bool down_else = link_at(n.c), down_then = !down_else && link_at(n.b);
      out.push_back(Link{n.a, down_then ? 1 : 0});
      s = down_else ? n.c : down_then ? n.b : -1;
    }
    return out;
  }
  // How many selects read node c as their condition.
  int selects_reading(int c) const {
    int k = 0;
    for (int r : consumers[c])
      if (r >= 0 && g.node(r).op == ir::Op::Select && g.node(r).a == c) ++k;
    return k;
  }

  // Every node that reads node i, directly or not (i excluded); indices ascend (topological).
  std::vector<bool> descendants(int i) const {
    std::vector<bool> d(g.size(), false);
    for (int j = i + 1; j < g.size(); ++j)
      for (int a : {g.node(j).a, g.node(j).b, g.node(j).c})
        if (a >= 0 && (a == i || d[a])) d[j] = true;
    return d;
  }

  // Every node the values of the selects conditioned on c read (the branches' ancestors).
  std::vector<bool> branch_ancestors(int c) const {
    std::vector<bool> anc(g.size(), false);
    std::vector<int> stack;
    for (int s : consumers[c])
      if (s >= 0 && g.node(s).op == ir::Op::Select && g.node(s).a == c)
        for (int b : {g.node(s).b, g.node(s).c}) stack.push_back(b);
    while (!stack.empty()) {
      const int j = stack.back();
      stack.pop_back();
      if (j < 0 || anc[j]) continue;
      anc[j] = true;
      for (int a : {g.node(j).a, g.node(j).b, g.node(j).c}) stack.push_back(a);
    }
    return anc;
  }

  const ir::Graph& g;
  // Per node: the nodes reading it (-1: a graph output).
  std::vector<std::vector<int>> consumers;
  std::vector<Affine> aff;
  // Per node: the node it is a function of alone (itself if none).
  std::vector<int> root;
  // Per node: its integer sources, when it is a lattice node.
  std::vector<Lattice> lattice;

 private:
  mutable std::map<std::pair<int, double>, bool> cell_cont;  // cell_continuous per floor argument, period
  std::uint64_t graph_hash() const {
    if (!hash_) hash_ = g.hash();
    return *hash_;
  }
  mutable std::optional<std::uint64_t> hash_;
  static ProcessMemo<std::pair<std::uint64_t, int>, bool>& probe_memo() {
    static ProcessMemo<std::pair<std::uint64_t, int>, bool> memo;
    return memo;
  }
  // (graph, node, the fixed comparisons its sub-DAG meets)
  using MomentKey = std::tuple<std::uint64_t, int, std::vector<std::pair<int, int>>>;
  static ProcessMemo<MomentKey, LatticeMoments>& moment_memo() {
    static ProcessMemo<MomentKey, LatticeMoments> memo;
    return memo;
  }
};

}  // namespace bl::compiler
