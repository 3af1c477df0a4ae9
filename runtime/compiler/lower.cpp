#include "compiler/lower.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "compiler/graph_facts.hpp"
#include "compiler/periodic_far_field.hpp"
#include "compiler/square_product.hpp"
#include "ir/atomics.hpp"
#include "ir/ranges.hpp"

namespace bl::compiler {
namespace {

using ir::Op;
using rules::Kind;
using rules::Rho;
using rules::Rule;

// A one-pass stat entry whose variance nothing reads (dead-variance elimination removed its
// readers) becomes its mean's own entry (calibrated float: gaussian fract 11.7 ns, fract_stat
// 16.9). Its Mean readers then read the call itself.
Program mean_only_stats(const Program& p) {
  const auto& fns = functions();
  const int n = static_cast<int>(p.insts.size());
  std::vector<char> demote(n, 0);
  for (int i = 0; i < n; ++i)
    demote[i] = p.insts[i].op == LOp::CallStat && fns[p.insts[i].fn].mean_entry >= 0;
  for (const Inst& in : p.insts)
    for (int j = 0; j < lop_arity(in); ++j)
      if (in.op != LOp::Mean) demote[in.arg[j]] = 0;
  for (int o : p.outputs) demote[o] = 0;
  Program out = p;
  out.insts.clear();
  out.outputs.clear();
  std::vector<int> pos(n, -1);
  for (int i = 0; i < n; ++i) {
    Inst in = p.insts[i];
    if (in.op == LOp::Mean && demote[in.arg[0]]) {
      pos[i] = pos[in.arg[0]];
      continue;
    }
    for (int j = 0; j < lop_arity(in); ++j) in.arg[j] = pos[in.arg[j]];
    if (demote[i]) in.op = LOp::Call, in.fn = fns[in.fn].mean_entry;
    pos[i] = static_cast<int>(out.insts.size());
    out.insts.push_back(in);
  }
  for (int o : p.outputs) out.outputs.push_back(pos[o]);
  return out;
}

// A lowered node: instruction ids of its mean and variance (-1: exactly zero, e.g. a constant).
struct Val {
  int mean = -1;
  int var = -1;
  int sd = -1;           // cached sqrt(var), or the input's sd
  int gx = -1, gy = -1;  // gradient of the mean w.r.t. screen x, y (computed on demand)
};

class Lowering {
 public:
  using Affine = GraphFacts::Affine;
  using Lattice = GraphFacts::Lattice;

  Lowering(const ir::Graph& g, const Schedule& s)
      : g_(g), s_(s), vals_(g.size()), ranges_(ir::node_ranges(g)), facts_(g), far_(g) {
    slope_.assign(g.size(), -1);
    exact_.assign(g.size(), false);
  }

  Program run() { return mean_only_stats(optimize(run_naive())); }

  Program run_naive() {
    p_.input_count = static_cast<int>(g_.inputs().size());
    for (const auto& in : g_.inputs()) p_.input_names.push_back(in.name);
    p_.texture_names = g_.textures();
    for (int i = 0; i < g_.size(); ++i) vals_[i] = node(i);
    bernoulli_mixtures();
    for (std::size_t k = 0; k < g_.outputs().size(); ++k) {
      p_.outputs.push_back(vals_[g_.outputs()[k]].mean);
      p_.output_names.push_back(g_.output_names()[k]);
    }
    for (const auto& n : notes_) p_.notes.push_back(n);
    return p_;
  }

 private:
  // ---- instruction builders ----
  int emit(Inst in) {
    p_.insts.push_back(in);
    return static_cast<int>(p_.insts.size()) - 1;
  }
  int k(float v) {
    Inst in;
    in.op = LOp::Const;
    in.k = v;
    return emit(in);
  }
  int op(LOp o, int a, int b = -1) {
    Inst in;
    in.op = o;
    in.arg[0] = a;
    in.arg[1] = b;
    return emit(in);
  }
  int add(int a, int b) { return op(LOp::Add, a, b); }
  int sub(int a, int b) { return op(LOp::Sub, a, b); }
  int mul(int a, int b) { return op(LOp::Mul, a, b); }
  int div(int a, int b) { return op(LOp::Div, a, b); }
  int sq(int a) { return mul(a, a); }
  int absolute(int a) { return op(LOp::Max, a, op(LOp::Neg, a)); }
  bool has(const std::string& fn) const { return find_function(fn) >= 0; }
  int call(const std::string& fn, std::initializer_list<int> args, bool stat = false) {
    const int f = find_function(fn);
    if (f < 0) throw std::logic_error("compiler: the generated table has no function " + fn);
    if (functions()[f].stat != stat || functions()[f].arity != static_cast<int>(args.size()))
      throw std::logic_error("compiler: " + fn + " has another signature than lowering expects");
    Inst in;
    in.op = stat ? LOp::CallStat : LOp::Call;
    in.fn = f;
    int j = 0;
    for (int a : args) in.arg[j++] = a;
    return emit(in);
  }
  // The pixel's value of input `slot`: its mean (InMean), footprint sd (InSd) or gradient.
  int input(LOp o, int slot) {
    Inst in;
    in.op = o;
    in.arg[0] = slot;
    return emit(in);
  }
  Val from_stat(int st) { return Val{op(LOp::Mean, st), op(LOp::Var, st)}; }
  void note(const std::string& s) { notes_.insert(s); }

  int sd(Val& v) {
    if (v.var < 0) return k(0);
    if (v.sd < 0) v.sd = op(LOp::Sqrt, v.var);
    return v.sd;
  }
  int scaled_sd(Val& v, const Rule& r) {
    const int s = sd(v);
    return r.sigma_scale == 1 ? s : mul(s, k(static_cast<float>(r.sigma_scale)));
  }

  // ---- nodes ----
  Val node(int i) {
    exact_[i] = false;
    Val v = node_rule(i);
    exact_[i] = exact_[i] || exact_linear(i);
    return far_field(i, v);
  }

  // The mean of node i is exact under its kernel: a fused pulse, window or step (exact at every
  // width), an atomic of an input's affine map, such a node under +, -, *, / with values that are
  // not random, or a select of such values by it. The far field leaves those alone (its mean and
  // series are sampled from the plain graph and truncated).
  bool exact_linear(int i) const {
    const ir::Node& n = g_.node(i);
    auto fixed = [&](int j) { return vals_[j].var < 0; };
    switch (n.op) {
      case Op::Neg:
        return exact_[n.a];
      case Op::Add:
      case Op::Sub:
        return (exact_[n.a] || fixed(n.a)) && (exact_[n.b] || fixed(n.b)) && (exact_[n.a] || exact_[n.b]);
      case Op::Mul:
        return (exact_[n.a] && fixed(n.b)) || (fixed(n.a) && exact_[n.b]);
      case Op::Div:
        return exact_[n.a] && fixed(n.b);
      case Op::Select:  // p a + (1 - p) b with p exact (a fused fract step) and a, b not random
        return exact_[n.a] && fixed(n.b) && fixed(n.c);
      case Op::Call: {
        // An atomic of one input's affine map under the Gaussian rule: the table's entry is the exact
        // convolution (fract(u) alone), unless fract takes its mode or the rule scales sigma.
        const Rule& r = s_.at(i);
        const int base = facts_.aff[n.a].base;
        if (r.kind != Kind::Gaussian || r.sigma_scale != 1 || base < 0 || g_.node(base).op != Op::Input ||
            vals_[n.a].var < 0)
          return false;
        return !fract_takes_mode(i);
      }
      default:
        return false;
    }
  }

  // A tiling's mask (PeriodicFarField::periodic_output) at footprints wider than its periods:
  // axis-aligned tilings take the series below; others blend into their spatial moments as the
  // footprint grows from kFarW0 to kFarW1 periods of the source they cover least (Gaussian rule
  // only: a box or tent kernel's harmonics decay like 1 / w, not exp(-w^2)).
  // Measured all-Gaussian, hexagonal tiles: 0.0788 -> 0.0558 (0.2/0.4: 0.0506, 0.4/0.6: 0.0592);
  // circles_none 0.02128 -> 0.02111.
  static constexpr float kFarW0 = 0.3f;
  static constexpr float kFarW1 = 0.5f;
  Val far_field(int i, Val v) {
    if (s_.at(i).kind != Kind::Gaussian || exact_[i] || !far_.periodic_output(i)) return v;
    const PeriodicFarField::Moments m = far_.spatial(i);
    if (!m.ok) return v;
    const PeriodicFarField::Axes ax = far_.axes(i);
    // The series reads the footprint from the inputs themselves: a plain pattern under a Gaussian
    // output still gets its far field and band (R is then the plain value).
    if (ax.ok) return axis_far_field(v.var < 0 ? Val{v.mean, k(0)} : v, m, ax);
    if (v.var < 0) return v;
    int w = -1;
    for (int j : far_.sources(i)) {
      Val& x = vals_[g_.node(j).a];
      if (x.var < 0) return v;
      const int wj = mul(sd(x), k(static_cast<float>(1 / far_.period(j))));
      w = w < 0 ? wj : op(LOp::Min, w, wj);
    }
    const int t = ramp(w, kFarW0, 1.0f / (kFarW1 - kFarW0));
    const int u = sub(k(1), t);
    Val out;
    out.mean = add(mul(u, v.mean), mul(t, k(static_cast<float>(m.mean))));
    const int m2 = add(mul(u, add(v.var, sq(v.mean))), mul(t, k(static_cast<float>(m.second))));
    out.var = op(LOp::NonNeg, sub(m2, sq(out.mean)));
    return out;
  }

  // An axis-aligned tiling (PeriodicFarField::axes): t_x = the far-field weight of axis x (0.3 to 0.5
  // periods), X_x = the damped series of the output averaged over the other axis where the series
  // converges (r_x: 0.035 to 0.045 periods along x), else the rule's value R:
  //   E = (1 - t_u)(1 - t_v) R + t_v X_u + t_u (1 - t_v) X_v
  // (both covered: X_u, exact there and tending to the mean; blending into the sampled mean instead
  // cost a stripe pattern 0.008 at 0.4 periods). An axis the output does not depend on counts as
  // covered (t = 1): a stripe pattern is its series.
  Val axis_far_field(const Val& v, const PeriodicFarField::Moments& m, const PeriodicFarField::Axes& ax) {
    int t[2], X[2];
    for (int axis = 0; axis < 2; ++axis) {
      const PeriodicFarField::Series& se = axis == 0 ? ax.u : ax.v;
      if (se.input < 0) {
        t[axis] = k(1);
        X[axis] = v.mean;  // not read: the other axis's weight (1 - t) is 0
        continue;
      }
      const int mean = input(LOp::InMean, se.input), sdev = input(LOp::InSd, se.input);
      const float L = static_cast<float>(se.period);
      const int w = mul(sdev, k(1 / L));
      t[axis] = ramp(w, kFarW0, 1.0f / (kFarW1 - kFarW0));
      const int r = ramp(w, 0.035f, 100.0f);
      // cos, sin of m theta by the angle-sum recurrence; the damping q^(m^2) by q^(2m + 1) steps.
      const int th = mul(k(6.2831853f), call(plain_name("fract"), {mul(mean, k(1 / L))}));
      const int c1 = call(plain_name("cos"), {th}), s1 = call(plain_name("sin"), {th});
      const int q = call(plain_name("exp"), {mul(k(-19.7392088f), sq(w))});  // exp(-2 pi^2 w^2)
      const int q2 = sq(q);
      int c = c1, s = s1, d = q, step = mul(q2, q);
      int S = k(static_cast<float>(se.a0));
      for (std::size_t mth = 0; mth < se.a.size(); ++mth) {
        if (mth > 0) {
          const int cn = sub(mul(c, c1), mul(s, s1));
          s = add(mul(s, c1), mul(c, s1));
          c = cn;
          d = mul(d, step);
          step = mul(step, q2);
        }
        int term = -1;
        if (std::fabs(se.a[mth]) >= PeriodicFarField::kSeriesFloor)
          term = mul(k(static_cast<float>(se.a[mth])), c);
        if (std::fabs(se.b[mth]) >= PeriodicFarField::kSeriesFloor) {
          const int bs = mul(k(static_cast<float>(se.b[mth])), s);
          term = term < 0 ? bs : add(term, bs);
        }
        if (term >= 0) S = add(S, mul(d, term));
      }
      X[axis] = add(mul(r, S), mul(sub(k(1), r), v.mean));
    }
    const int nu = sub(k(1), t[0]), nv = sub(k(1), t[1]);
    const int near = mul(nu, nv);
    Val out;
    out.mean = add(add(mul(near, v.mean), mul(t[1], X[0])), mul(mul(t[0], nv), X[1]));
    // The second moment: the rule's where no axis is covered, the spatial one elsewhere.
    const int m2 =
        add(mul(near, add(v.var, sq(v.mean))), mul(sub(k(1), near), k(static_cast<float>(m.second))));
    out.var = op(LOp::NonNeg, sub(m2, sq(out.mean)));
    return out;
  }

  Val node_rule(int i) {
    const ir::Node& n = g_.node(i);
    const Rule& r = s_.at(i);
    switch (n.op) {
      case Op::Const:
        return Val{k(static_cast<float>(n.value)), -1};
      case Op::Input: {
        const int slot = static_cast<int>(n.value);
        Val v;
        v.mean = input(LOp::InMean, slot);
        if (g_.inputs()[slot].varying && r.kind != Kind::None) {
          v.sd = input(LOp::InSd, slot);
          v.var = sq(v.sd);
        }
        return v;
      }
      default:
        break;
    }
    if (!fixed_.empty()) {  // a branch of a Bernoulli mixture: the comparison is known
      if (const auto f = fixed_.find(i); f != fixed_.end()) return Val{k(static_cast<float>(f->second)), -1};
      if (const int p = GraphFacts::passed(n, fixed_); p >= 0) return vals_[p];
    }
    std::vector<Val*> args;
    for (int a : {n.a, n.b, n.c})
      if (a >= 0) args.push_back(&vals_[a]);
    bool random = false;
    for (Val* a : args) random = random || a->var >= 0;
    if (random && r.kind != Kind::MonteCarlo && !lattice_boundary(i)) {
      Val pv;
      if (floor_pulse(i, r, pv) || fract_window(i, r, pv) || fract_step(i, r, pv)) {
        exact_[i] = true;
        return pv;
      }
    }
    if (r.kind == Kind::None || !random) return Val{plain(n, args), -1};
    if (r.kind != Kind::MonteCarlo && lattice_boundary(i)) return lattice_mixture(i, r);
    if (r.kind == Kind::MonteCarlo) return monte_carlo(i, n, r, args);
    if (n.op == Op::Call) {
      if (r.kind == Kind::Dorn) return in_range(i, call_node(i, n, r, *args[0]));
      Val v = call_node(i, n, r, *args[0]);
      if (r.kind == Kind::Gaussian) abs_of_sin(n, v);
      return v;
    }
    if (n.op == Op::Texture) return texture_node(n, r, *args[0], *args[1]);
    if (n.op == Op::Neg) return Val{op(LOp::Neg, args[0]->mean), args[0]->var, args[0]->sd};
    if (r.kind == Kind::Dorn) return in_range(i, dorn(n, r, args));
    if (r.kind != Kind::Gaussian)
      note(std::string(rules::kind_name(r.kind)) + " on " + ir::op_name(n.op) + " -> gaussian (rho 0)");
    return gaussian(i, n, r, args);
  }

  // The operation on plain values (also the Monte Carlo integrand).
  int plain(const ir::Node& n, const std::vector<int>& x) {
    switch (n.op) {
      case Op::Add:
        return add(x[0], x[1]);
      case Op::Sub:
        return sub(x[0], x[1]);
      case Op::Mul:
        return mul(x[0], x[1]);
      case Op::Div:
        return div(x[0], x[1]);
      case Op::Neg:
        return op(LOp::Neg, x[0]);
      case Op::Min:
        return op(LOp::Min, x[0], x[1]);
      case Op::Max:
        return op(LOp::Max, x[0], x[1]);
      case Op::Less:
        return op(LOp::Less, x[0], x[1]);
      case Op::Select:
        return add(mul(x[0], x[1]), mul(sub(k(1), x[0]), x[2]));
      case Op::Mod: {
        const int c = k(static_cast<float>(n.value));
        return sub(x[0], mul(c, call(plain_name("floor"), {div(x[0], c)})));
      }
      case Op::Call:
        return call(plain_name(ir::atomic_name(n.atomic)), {x[0]});
      case Op::Texture: {
        Inst in;
        in.op = LOp::TexPlain;
        in.tex = static_cast<int>(n.value);
        in.channel = n.atomic;
        in.arg[0] = x[0];
        in.arg[1] = x[1];
        return emit(in);
      }
      default:
        throw std::logic_error("compiler: plain() of a leaf");
    }
  }
  int plain(const ir::Node& n, const std::vector<Val*>& args) {
    std::vector<int> x;
    for (Val* a : args) x.push_back(a->mean);
    return plain(n, x);
  }

  Val monte_carlo(int i, const ir::Node& n, const Rule& r, const std::vector<Val*>& args) {
    const int dims = static_cast<int>(args.size());
    const std::vector<float> z = mc_normals(i, r.samples, dims);
    std::vector<int> s(dims);
    for (int d = 0; d < dims; ++d) s[d] = args[d]->var >= 0 ? scaled_sd(*args[d], r) : -1;
    int sum = -1;
    std::vector<int> ys;
    for (int j = 0; j < r.samples; ++j) {
      std::vector<int> x(dims);
      for (int d = 0; d < dims; ++d)
        x[d] = s[d] < 0 ? args[d]->mean : add(args[d]->mean, mul(s[d], k(z[j * dims + d])));
      const int y = plain(n, x);
      sum = sum < 0 ? y : add(sum, y);
      ys.push_back(y);
    }
    const int inv_n = k(1.0f / static_cast<float>(r.samples));
    Val v;
    v.mean = mul(sum, inv_n);
    if (ys.size() == 2) {
      // ((y0 - m)^2 + (y1 - m)^2) / 2 = ((y0 - y1) / 2)^2: one difference, and the sd |y0 - y1| / 2
      // without a sqrt where a later rule reads it.
      const int d = mul(sub(ys[0], ys[1]), k(0.5f));
      v.var = sq(d);
      v.sd = absolute(d);
      return v;
    }
    // The sample variance from deviations, not E[y^2] - E[y]^2: that cancels in float for a value
    // far from 0 (y ~ 25, sd 1e-5 reported sd ~ 6e-3; found by the convergence test on value noise).
    int dev = -1;
    for (int y : ys) dev = dev < 0 ? sq(sub(y, v.mean)) : add(dev, sq(sub(y, v.mean)));
    v.var = mul(dev, inv_n);
    return v;
  }

  // Kernel entry f (or f^2) by name, with the fallback chain for atomics a kernel cannot smooth.
  std::string kernel_for(const std::string& want, const std::string& f) {
    for (const std::string& kern : {want, std::string("gaussian"), std::string("tent"), std::string("box")})
      if (has(kernel_name(kern, f, false))) {
        if (kern != want) note(want + " " + f + " -> " + kern + " (no " + want + " closed form)");
        return kern;
      }
    throw std::logic_error("compiler: no kernel smooths " + f);
  }

  Val convolve(const std::string& kern, const std::string& f, int m, int s, int var_in) {
    // Both moments from one pass where the table has it (gaussian fract, floor, ceil: calibrated
    // float fract and fract^2 cost 11.7 + 13.7 ns apart, 16.9 together).
    if (has(stat_name(kern, f))) return from_stat(call(stat_name(kern, f), {m, s}, true));
    Val v;
    v.mean = call(kernel_name(kern, f, false), {m, s});
    const int a = ir::atomic_index(f);
    if (a >= 0 && ir::atomic_indicator(a)) {
      // f^2 = f (step, square, pulse30): the variance m (1 - m) without a second smoothed call
      // (gaussian step_sq cost 3.7 ns beside step, square_sq 13), and no E[f^2] - m^2 to cancel.
      v.var = op(LOp::NonNeg, mul(v.mean, sub(k(1.0f), v.mean)));
    } else if (has(kernel_name(kern, f, true))) {
      v.var = op(LOp::NonNeg, sub(call(kernel_name(kern, f, true), {m, s}), sq(v.mean)));
    } else {
      note(kern + " " + f + "_sq is not in the table: the input variance passes through");
      v.var = var_in;
    }
    return v;
  }

  // Call node i is a fract whose jump the output does not see (wrap-continuous consumers, or cells
  // the output hides): under the Gaussian rule it reports the side its footprint holds (mode_fract).
  bool fract_takes_mode(int i) const {
    const ir::Node& n = g_.node(i);
    return n.op == Op::Call && std::string(ir::atomic_name(n.atomic)) == "fract" &&
           (facts_.wrap_continuous(i) || facts_.cell_continuous(n.a));
  }

  Val call_node(int i, const ir::Node& n, const Rule& r, Val& x) {
    const std::string f = ir::atomic_name(n.atomic);
    const int s = scaled_sd(x, r);
    if (r.kind == Kind::Gaussian) {
      if (fract_takes_mode(i)) return mode_fract(x.mean, s);
      if (f == "floor" || f == "ceil") return shifted(f, x.mean, s, x.var);
    }
    switch (r.kind) {
      case Kind::Dorn: {
        // Dorn: Gaussian mean, and the output sd is the input's (the "sample spacing" heuristic).
        const std::string kern = kernel_for("gaussian", f);
        const int mean = call(kernel_name(kern, f, false), {x.mean, s});
        // Our one change to Dorn's heuristic: a value confined to [lo, hi] has sd <= (hi - lo) / 2,
        // so a bounded atomic (saturate, fract, sin, ...) caps the sd it passes on; without the cap a
        // huge footprint near the horizon flows through saturate into pow8 and overflows.
        double lo, hi;
        ir::atomic_range(n.atomic, &lo, &hi);
        if (std::isfinite(lo) && std::isfinite(hi)) {
          const int capped = op(LOp::Min, x.sd >= 0 ? x.sd : sd(x), k(static_cast<float>((hi - lo) / 2)));
          return Val{mean, sq(capped), capped};
        }
        return Val{mean, x.var, x.sd};
      }
      case Kind::Gaussian:
        return convolve(kernel_for("gaussian", f), f, x.mean, s, x.var);
      case Kind::Box:
        return convolve(kernel_for("box", f), f, x.mean, s, x.var);
      case Kind::Tent:
        return convolve(kernel_for("tent", f), f, x.mean, s, x.var);
      case Kind::Rule1:
      case Kind::Rule2:
      case Kind::Rule3: {
        const std::string name = r.kind == Kind::Rule1   ? "bl::rule1::" + r.kernel + "::" + f
                                 : r.kind == Kind::Rule2 ? "bl::rule2::" + f
                                                         : "bl::rule3::" + f;
        if (has(name)) return from_stat(call(name, {x.mean, s}, true));
        note(to_string(r) + " " + f + " -> gaussian (no such rule in the table)");
        return convolve(kernel_for("gaussian", f), f, x.mean, s, x.var);
      }
      default:
        throw std::logic_error("compiler: call_node with rule " + to_string(r));
    }
  }

  // A node the fusions below may smooth as part of a function of its argument: its rule is a kernel
  // (gaussian, box or tent) and it is no lattice boundary. The two nodes of a fused pair
  // (GraphFacts::floor_pulse, fract_windows) must each be so with a random argument, and both be
  // smoothed by one kernel at one width.
  bool kernel_rule(int j) {
    const Kind kj = s_.at(j).kind;
    return (kj == Kind::Gaussian || kj == Kind::Box || kj == Kind::Tent) && !facts_.lattice_boundary(j);
  }
  bool kernel_smoothed(int j) { return kernel_rule(j) && vals_[g_.node(j).a].var >= 0; }
  bool one_kernel(int a, int b) {
    return kernel_smoothed(a) && kernel_smoothed(b) && s_.at(a).kind == s_.at(b).kind &&
           s_.at(a).sigma_scale == s_.at(b).sigma_scale;
  }

  // floor(y + 1/2) - floor(y) = 1 - square(y) (1 where fract(y) >= 1/2: a checkerboard's or a
  // stripe's pulse). Both floors smoothed by one kernel at one width: one smoothed square wave
  // instead of two smoothed floors (calibrated float: gaussian floor 10.9 ns + the plain floor of
  // its shift, twice, against square 12.1; box 5.7 x 2 against 8.0). The mean is the floors'
  // difference exactly (the expectation is linear); the variance is the indicator's p (1 - p), where
  // two floors would need their correlation (under a None rule the node keeps no variance).
  bool floor_pulse(int i, const Rule& r, Val& out) {
    const auto fp = facts_.floor_pulse(i);
    if (!fp || !one_kernel(fp->lower, fp->upper)) return false;
    const Rule& rf = s_.at(fp->lower);
    Val& y = vals_[g_.node(fp->lower).a];
    const std::string kern = kernel_for(rules::kind_name(rf.kind), "square");
    const int p = call(kernel_name(kern, "square", false), {y.mean, scaled_sd(y, rf)});
    const int pulse = sub(k(1), p);
    out.mean = fp->sign > 0 ? pulse : op(LOp::Neg, pulse);
    out.var = r.kind == Kind::None ? -1 : op(LOp::NonNeg, mul(p, pulse));
    return true;
  }

  // step(fract(y) - lo) * step(hi - fract(y)), 0 < lo < hi < 1 (either order): the indicator of
  // fract(y) in [lo, hi], a brick's or a tile's inside, equals (hi - lo) - fract(y - lo) + fract(y - hi)
  // for every y (fract_interval). Both steps smoothed by one kernel at one width: the indicator's exact
  // mean under that kernel on y from two mean-only fract entries (calibrated float: box 2 x 5.75 ns,
  // tent 2 x 6.5),
  // where the steps alone read fract's variance (gaussian fract_stat 17.5) and multiply two smoothed
  // steps as if independent; the variance is the indicator's p (1 - p).
  // A product chain written left to right (step(fx - lo) * step(hi - fx) * step(fy - lo) * step(hi - fy),
  // a brick's inside) puts the second pair in two nodes: ((Q * A) * B) with A, B one window is fused
  // here as Q * window, Q and the window independent (the variance of a product of independent values).
  bool fract_window(int i, const Rule& r, Val& out) {
    for (const GraphFacts::FractWindow& w : facts_.fract_windows(i)) {
      if (!one_kernel(w.a, w.b) || vals_[g_.node(w.fract).a].var < 0) continue;
      const Rule& rs = s_.at(w.a);
      Val& y = vals_[g_.node(w.fract).a];
      const std::string fr = kernel_name(kernel_for(rules::kind_name(rs.kind), "fract"), "fract", false);
      const int s = scaled_sd(y, rs);
      const int y_lo = sub(y.mean, k(static_cast<float>(w.lo)));
      const int y_hi = sub(y.mean, k(static_cast<float>(w.hi)));
      const int p = fract_interval(fr, k(static_cast<float>(w.hi - w.lo)), y_lo, s, y_hi, s);
      const int pvar = r.kind == Kind::None ? -1 : indicator_var(p);
      if (w.other < 0) {
        out = Val{p, pvar};
        return true;
      }
      const Val& x = vals_[w.other];
      out = Val{mul(x.mean, p), -1};
      if (r.kind != Kind::None) {
        const int vw = mul(pvar, sq(x.mean));  // Var(XW) = Vx Vw + Vx mw^2 + Vw mx^2
        out.var = x.var < 0 ? vw : add(mul(x.var, add(pvar, sq(p))), vw);
      }
      return true;
    }
    return false;
  }

  // step(c - fract(y)), 0 <= c <= 1, the indicator of fract(y) <= c, equals c - fract(y) + fract(y - c)
  // for almost every y (step(fract(y) - c) is one minus it; less(fract(y), c) and less(c, fract(y))
  // are the same indicators). The step smoothed by a kernel with a random argument: the indicator's
  // mean under that kernel on y from two mean-only fract entries (fract_interval), where the step
  // alone reads fract's variance and smooths as if fract(y) were unimodal (it is not next to fract's
  // jump); the variance is the indicator's p (1 - p). Exact for a constant edge; an edge node (its
  // range inside [0, 1]) enters through its mean and y - c's variance (Var y + Var c, the two taken
  // as independent).
  bool fract_step(int i, const Rule& r, Val& out) {
    const auto fs = facts_.fract_step(i);
    if (!fs || !kernel_rule(i) || vals_[g_.node(fs->fract).a].var < 0) return false;
    if (fs->edge >= 0 && !(ranges_[fs->edge].lo >= 0 && ranges_[fs->edge].hi <= 1)) return false;
    Val y = vals_[g_.node(fs->fract).a];
    if (fs->period != 1) {  // mod(x, P) = P fract(x / P)
      const float ip = static_cast<float>(1 / fs->period);
      y = Val{mul(y.mean, k(ip)), mul(y.var, k(ip * ip))};
    }
    const std::string fr = kernel_name(kernel_for(rules::kind_name(r.kind), "fract"), "fract", false);
    // fract(y) in [0, c]: y - c's sd is y's for a constant edge, sqrt(Var y + Var c) for an edge node.
    const Val* e = fs->edge < 0 ? nullptr : &vals_[fs->edge];
    const int c = e ? e->mean : k(static_cast<float>(fs->c));
    const int sd_y = scaled_sd(y, r);
    Val d{sub(y.mean, c), e && e->var >= 0 ? add(y.var, e->var) : y.var};
    const int sd_d = e ? scaled_sd(d, r) : sd_y;
    const int below = fract_interval(fr, c, y.mean, sd_y, d.mean, sd_d);
    const int p = fs->dir < 0 ? below : sub(k(1), below);
    out = Val{p, indicator_var(p)};
    return true;
  }

  // The kernel's mean of the indicator of fract(y) in [lo, hi] (0 <= lo <= hi <= 1, width = hi - lo):
  // width - fract(y - lo) + fract(y - hi) for every y, from two mean-only fract entries `fr` at
  // (y - lo, its sd) and (y - hi, its sd).
  int fract_interval(const std::string& fr, int width, int y_lo, int sd_lo, int y_hi, int sd_hi) {
    const int at_lo = call(fr, {y_lo, sd_lo});
    const int at_hi = call(fr, {y_hi, sd_hi});
    return add(sub(width, at_lo), at_hi);
  }
  int indicator_var(int p) { return op(LOp::NonNeg, mul(p, sub(k(1), p))); }

  // fract of N(m, s^2) reported as the side of the nearest jump that holds most of the kernel: the
  // moments of a normal truncated at the jump (the 2018 smoothing code's "probabilistic" fract, with
  // a Gaussian instead of a tent). Blended linearly (first and second moments) into the full
  // Gaussian rule as s grows from kModeS0 to kModeS1 periods, where both sides carry weight.
  // Thresholds measured on circles_none (all-Gaussian / MSAA-16 error: 0.05/0.10 -> 1.70, 0.10/0.25
  // -> 1.15, 0.15/0.40 -> 0.93, 0.25/0.60 -> 0.90, 0.30/0.80 -> 0.92); the 2018 tent widths 1/4 and
  // 1/2 period correspond to 0.05/0.10.
  static constexpr float kModeS0 = 0.25f;
  static constexpr float kModeS1 = 0.6f;
  Val mode_fract(int m, int s) {
    const int d = sub(call(plain_name("fract"), {add(m, k(0.5f))}), k(0.5f));  // m - round(m)
    const int ad = absolute(d);
    const int safe_s = op(LOp::Max, s, k(1e-30f));
    const int q = div(ad, safe_s);
    const int pdf = mul(k(0.3989422804f), call(plain_name("exp"), {mul(k(-0.5f), sq(q))}));
    const int cdf = call(kernel_name("gaussian", "step", false), {ad, s});  // Phi(|d|/s) >= 1/2
    const int sl = mul(s, div(pdf, cdf));                                   // s lambda
    const int neg = op(LOp::Less, d, k(0));
    // Dominant side: d < 0 -> fract = x - (k - 1), mean 1 + d - s lambda; d >= 0 -> d + s lambda.
    const int mm = add(add(d, neg), mul(sub(k(1), mul(k(2), neg)), sl));
    const int vm = op(LOp::NonNeg, sub(sub(sq(s), mul(ad, sl)), sq(sl)));
    const Val full = convolve("gaussian", "fract", m, s, -1);
    const int fm = full.mean;
    const int f2 = add(full.var, sq(fm));
    const int t = mode_blend(s);
    // (1 - t) a + t b, not a + t (b - a): the mode's moments grow like s^2 and would cancel b away.
    const int u = sub(k(1), t);
    Val v;
    v.mean = add(mul(u, mm), mul(t, fm));
    const int m2 = add(mul(u, add(vm, sq(mm))), mul(t, f2));
    v.var = op(LOp::NonNeg, sub(m2, sq(v.mean)));
    return v;
  }

  // 0 below kModeS0, 1 above kModeS1: the weight of the full rule against the mode's.
  int mode_blend(int s) { return ramp(s, kModeS0, 1.0f / (kModeS1 - kModeS0)); }

  // saturate((x - lo) * inv_width): 0 below lo, 1 from lo + 1 / inv_width on, linear between.
  int ramp(int x, float lo, float inv_width) {
    return call(plain_name("saturate"), {mul(sub(x, k(lo)), k(inv_width))});
  }

  // floor and ceil commute with integer shifts: smoothing at m - K, K = floor(m) (plain, exact in
  // float below 2^24), keeps the moments near 0, so E[f^2] - E[f]^2 does not cancel (floor at 40.7,
  // sd 0.01 reported a variance of 1.2e-4 from float rounding; the true one is ~1e-300).
  Val shifted(const std::string& f, int m, int s, int var_in) {
    const int K = call(plain_name("floor"), {m});
    Val v = convolve("gaussian", f, sub(m, K), s, var_in);
    v.mean = add(v.mean, K);
    return v;
  }

  // A texture is a discrete function: every smoothing rule reads the mean and mean-of-squares
  // pyramids at the footprint's level (clamped-domain paper, eqs. 21-22); Monte Carlo samples the
  // texture directly (monte_carlo above), none reads level 0.
  Val texture_node(const ir::Node& n, const Rule& r, Val& u, Val& v) {
    Inst in;
    in.op = LOp::TexStat;
    in.tex = static_cast<int>(n.value);
    in.channel = n.atomic;
    in.arg[0] = u.mean;
    in.arg[1] = v.mean;
    in.arg[2] = u.var >= 0 ? scaled_sd(u, r) : k(0);
    in.arg[3] = v.var >= 0 ? scaled_sd(v, r) : k(0);
    return from_stat(emit(in));
  }

  // Dorn's mean is a heuristic (a Gaussian of the *input's* sd pushed through the node: a saturate
  // with mean 1 and capped sd 0.5 feeding pow8 gives E[X^8] = 28 for X ~ N(1, 0.5^2), where
  // pow8(saturate(.)) <= 1): a mean of values in the node's range lies in that range, so it is
  // clamped there (docs/runtime.md, "Honest metrics").
  Val in_range(int i, Val v) {
    const ir::Interval& r = ranges_[i];
    if (std::isfinite(r.lo)) v.mean = op(LOp::Max, v.mean, k(static_cast<float>(r.lo)));
    if (std::isfinite(r.hi)) v.mean = op(LOp::Min, v.mean, k(static_cast<float>(r.hi)));
    return v;
  }

  // Dorn et al. 2015 with Yang & Barnes' improvement (4.3): sd adds over +/-, scales by a constant
  // factor, multiplies/divides otherwise, and averages over other operators.
  Val dorn(const ir::Node& n, const Rule& r, const std::vector<Val*>& a) {
    auto s = [&](int j) { return sd(*a[j]); };
    const bool ca = a[0]->var<0, cb = a.size()> 1 && a[1]->var < 0;
    Val v;
    switch (n.op) {
      case Op::Add:
      case Op::Sub:
        v.mean = plain(n, a);
        if (ca || cb) return Val{v.mean, ca ? a[1]->var : a[0]->var, ca ? a[1]->sd : a[0]->sd};
        v.sd = add(s(0), s(1));
        v.var = sq(v.sd);
        return v;
      // Dorn's heuristics work on sds (not variances): products of variances overflow float for
      // the footprints near a horizon (sd ~ 1e3 in uv), products of sds do not.
      case Op::Mul:
        v.mean = plain(n, a);
        v.sd = ca ? mul(absolute(a[0]->mean), s(1)) : cb ? mul(absolute(a[1]->mean), s(0)) : mul(s(0), s(1));
        v.var = sq(v.sd);
        return v;
      case Op::Div:
        v.mean = plain(n, a);
        v.sd = cb ? div(s(0), absolute(a[1]->mean)) : div(s(0), op(LOp::Max, s(1), k(1e-30f)));
        v.var = sq(v.sd);
        return v;
      case Op::Mod: {
        const float c = static_cast<float>(n.value);
        v.mean = mul(k(c), call(kernel_name("gaussian", "fract", false),
                                {div(a[0]->mean, k(c)), mul(scaled_sd(*a[0], r), k(1.0f / std::fabs(c)))}));
        v.sd = op(LOp::Min, s(0), k(std::fabs(c) / 2));  // the range cap, as for atomics
        v.var = sq(v.sd);
        return v;
      }
      default:
        break;
    }
    // min, max, select, less: average of the inputs' sds.
    int sum = -1, count = 0;
    for (Val* x : a)
      if (x->var >= 0) {
        sum = sum < 0 ? sd(*x) : add(sum, sd(*x));
        ++count;
      }
    const int avg = count == 1 ? sum : mul(sum, k(1.0f / static_cast<float>(count)));
    v.sd = avg;
    v.var = sq(avg);
    if (n.op == Op::Less) {
      const int sc = r.sigma_scale == 1 ? avg : mul(avg, k(static_cast<float>(r.sigma_scale)));
      v.mean = call(kernel_name("gaussian", "step", false), {sub(a[1]->mean, a[0]->mean), sc});
    } else {
      v.mean = plain(n, a);
    }
    return v;
  }

  int rho(int i, const ir::Node& n, const Rule& r) {
    if (r.kind != Kind::Gaussian) return k(0);
    if (r.rho == Rho::Zero) {
      const int sh = shared_rho(n);
      return sh < 0 ? k(0) : sh;
    }
    if (r.rho == Rho::Constant) return k(static_cast<float>(r.rho_value));
    Val& a = grad(n.a);
    Val& b = grad(n.b);
    (void)i;
    const int dot = add(mul(a.gx, b.gx), mul(a.gy, b.gy));
    if (r.rho == Rho::Covariance) {
      const Affine &fa = facts_.aff[n.a], &fb = facts_.aff[n.b];
      if (fa.base >= 0 && fa.base == fb.base && fa.beta != 0 && fb.beta != 0)
        return k(fa.beta * fb.beta > 0 ? 1.0f : -1.0f);  // affine in one base: exact
      // Cov(A, B) ~ sigma_px^2 (ga . gb) with Stein slopes (smoothed_slope): it fades as a wide
      // footprint averages the jumps out, where the normalised dot product stays at +-1.
      // sigma_px^2 is read off input 0 (the surface u): its sd over its screen gradient's length.
      const int s0 = input(LOp::InSd, 0), g0x = input(LOp::InGradX, 0), g0y = input(LOp::InGradY, 0);
      const int sig2 = div(sq(s0), op(LOp::Max, add(sq(g0x), sq(g0y)), k(1e-30f)));
      const int den = op(LOp::Max, mul(sd(vals_[n.a]), sd(vals_[n.b])), k(1e-30f));
      return op(LOp::Min, op(LOp::Max, div(mul(dot, sig2), den), k(-1)), k(1));
    }
    const int na = add(sq(a.gx), sq(a.gy)), nb = add(sq(b.gx), sq(b.gy));
    // Zero gradients (a constant-in-screen input) give rho 0 rather than 0/0.
    const int den = op(LOp::Sqrt, op(LOp::Max, mul(na, nb), k(1e-30f)));
    return op(LOp::Min, op(LOp::Max, div(dot, den), k(-1)), k(1));
  }

  // abs(sin(X)), X ~ N(m, s^2), both nodes Gaussian: abs of a Gaussian with sin's moments is 0.564
  // for wide kernels where E|sin X| -> 2/pi = 0.637 (fire's far field: its octaves are |sin|). For
  // s >= 0.15 the Fourier series |sin x| = 2/pi - 4/pi sum cos(2kx) / (4k^2 - 1) gives
  // E|sin X| = 2/pi - 4/pi sum cos(2km) e^{-2k^2 s^2} / (4k^2 - 1), 8 terms (truncation < 1e-4 at
  // s = 0.15); below, the composed rule (error < 2e-4 at s <= 0.1). Var = E[sin^2] - mean^2.
  void abs_of_sin(const ir::Node& n, Val& v) {
    if (std::string(ir::atomic_name(n.atomic)) != "abs" || v.var < 0) return;
    const ir::Node& sn = g_.node(n.a);
    if (sn.op != Op::Call || std::string(ir::atomic_name(sn.atomic)) != "sin") return;
    if (s_.at(n.a).kind != Kind::Gaussian) return;
    Val& x = vals_[sn.a];
    if (x.var < 0) return;
    const int s = scaled_sd(x, s_.at(n.a));
    const int c1 = call(plain_name("cos"), {mul(k(2), x.mean)});
    const int q = call(plain_name("exp"), {mul(k(-2), sq(s))});
    const int q2 = sq(q);
    int c_prev = k(1), c_k = c1, d_k = q, qp = q, sum = -1;
    for (int kk = 1; kk <= 8; ++kk) {
      if (kk > 1) {
        const int c_next = sub(mul(mul(k(2), c1), c_k), c_prev);
        c_prev = c_k, c_k = c_next;
        qp = mul(qp, q2);    // q^(2k - 1)
        d_k = mul(d_k, qp);  // q^(k^2)
      }
      const int t = mul(mul(c_k, d_k), k(static_cast<float>(4.0 / M_PI / (4.0 * kk * kk - 1))));
      sum = sum < 0 ? t : add(sum, t);
    }
    const int four = sub(k(static_cast<float>(2.0 / M_PI)), sum);
    const int e2 = sub(k(0.5f), mul(k(0.5f), mul(c1, q)));
    const int four_var = op(LOp::NonNeg, sub(e2, sq(four)));
    const int w = op(LOp::Less, s, k(0.15f)), nw = sub(k(1), w);
    v.mean = add(mul(w, v.mean), mul(nw, four));
    v.var = add(mul(w, v.var), mul(nw, four_var));
    v.sd = -1;
  }

  // (alpha_a + beta_a SA) (alpha_b + beta_b SB) with SA, SB square waves of affine functions of one
  // root R whose frequencies have an integer ratio (zigzag's hue and band): exact mean and variance
  // from E[SA SB] (compiler/square_product.hpp), E[SA] and E[SB] as smoothed. False: not that form.
  bool square_pair_product(const ir::Node& n, const Rule& r, Val& out) {
    const Affine &fa = facts_.aff[n.a], &fb = facts_.aff[n.b];
    auto is_square = [&](int j) {
      return j >= 0 && g_.node(j).op == Op::Call &&
             std::string(ir::atomic_name(g_.node(j).atomic)) == "square";
    };
    if (!is_square(fa.base) || !is_square(fb.base) || fa.base == fb.base || fa.beta == 0 || fb.beta == 0)
      return false;
    const int sa = fa.base, sb = fb.base;
    const Affine &xa = facts_.aff[g_.node(sa).a], &xb = facts_.aff[g_.node(sb).a];
    if (xa.base < 0 || xa.base != xb.base || xa.beta == 0 || xb.beta == 0) return false;
    Val& root = vals_[xa.base];
    if (root.var < 0 || vals_[sa].var < 0 || vals_[sb].var < 0) return false;
    // E[SA], E[SB] must be the same Gaussian expectations as E[SA SB], or the covariance is off.
    if (s_.at(sa).kind != Kind::Gaussian || s_.at(sb).kind != Kind::Gaussian) return false;
    // The slower wave's argument x = beta_s R + alpha_s; the faster one's is q x + d, q an integer.
    const bool a_slow = std::fabs(xa.beta) <= std::fabs(xb.beta);
    const Affine &slow = a_slow ? xa : xb, &fast = a_slow ? xb : xa;
    const double ratio = fast.beta / slow.beta, q = std::round(ratio);
    if (q == 0 || std::fabs(q) > 16 || std::fabs(ratio - q) > 1e-9 * std::fabs(ratio)) return false;
    const auto pieces = square_product_intervals(static_cast<int>(q), fast.alpha - q * slow.alpha);
    const int mx = add(mul(k(static_cast<float>(slow.beta)), root.mean), k(static_cast<float>(slow.alpha)));
    const int sx = mul(k(static_cast<float>(std::fabs(slow.beta))), scaled_sd(root, r));
    const std::string fr = kernel_name("gaussian", "fract", false);
    double width = 0;
    int both = -1;  // E[SA SB] - total width
    for (const auto& [lo, hi] : pieces) {
      width += hi - lo;
      const int t = sub(call(fr, {sub(mx, k(static_cast<float>(hi))), sx}),
                        call(fr, {sub(mx, k(static_cast<float>(lo))), sx}));
      both = both < 0 ? t : add(both, t);
    }
    const int p = both < 0 ? k(0) : add(k(static_cast<float>(width)), both);
    const int ea = vals_[sa].mean, eb = vals_[sb].mean;
    // E[(al + be SA)(al' + be' SB)] for indicators SA, SB.
    auto expect = [&](double al, double be, double al2, double be2) {
      return add(add(k(static_cast<float>(al * al2)), mul(k(static_cast<float>(al * be2)), eb)),
                 add(mul(k(static_cast<float>(be * al2)), ea), mul(k(static_cast<float>(be * be2)), p)));
    };
    out.mean = expect(fa.alpha, fa.beta, fb.alpha, fb.beta);
    // Squares: (al + be S)^2 = al^2 + (2 al be + be^2) S.
    const int m2 = expect(fa.alpha * fa.alpha, 2 * fa.alpha * fa.beta + fa.beta * fa.beta,
                          fb.alpha * fb.alpha, 2 * fb.alpha * fb.beta + fb.beta * fb.beta);
    out.var = op(LOp::NonNeg, sub(m2, sq(out.mean)));
    return true;
  }

  // rho = 0 known while lowering: the covariance terms are left out rather than multiplied by 0,
  // so what feeds them is never written (optimize() also folds x * 0 to 0, e.g. zero derivative
  // terms, but only after the operands were lowered).
  bool rho_zero(const Rule& r) const {
    return r.rho == Rho::Zero || (r.rho == Rho::Constant && r.rho_value == 0);
  }

  Val gaussian(int i, const ir::Node& n, const Rule& r, const std::vector<Val*>& a) {
    Val v;
    const bool ca = a[0]->var<0, cb = a.size()> 1 && a[1]->var < 0;
    // A product of powers of one base (x * x * x, pow2(x) * pow2(x)) is x^n: its exact Gaussian
    // moments from the pow<n> entry (n <= 8), not a product of correlated factors.
    if (n.op == Op::Mul) {
      const std::pair<int, int> pa = facts_.monomial(n.a), pb = facts_.monomial(n.b);
      const int deg = pa.second + pb.second;
      if (pa.first == pb.first && deg >= 2 && deg <= 8 && vals_[pa.first].var >= 0) {
        Val& x = vals_[pa.first];
        return convolve("gaussian", "pow" + std::to_string(deg), x.mean, scaled_sd(x, r), x.var);
      }
    }
    if (n.op == Op::Mul) {
      Val sp;
      if (square_pair_product(n, r, sp)) return sp;
    }
    // Identical operands (hash-consing gives them one node id) are perfectly correlated: x - x = 0,
    // x + x = 2x, x / x = 1 exactly, and x * x is pow2 with its exact Gaussian moments.
    if (n.op != Op::Select && n.b >= 0 && n.a == n.b) {
      switch (n.op) {
        case Op::Sub:
          return Val{k(0), -1};
        case Op::Div:
          return Val{k(1), -1};
        case Op::Add:
          return Val{mul(k(2), a[0]->mean), mul(k(4), a[0]->var)};
        case Op::Min:
        case Op::Max:
          return *a[0];
        case Op::Less:
          return Val{k(0), -1};
        case Op::Mul:
          return convolve("gaussian", "pow2", a[0]->mean, scaled_sd(*a[0], r), a[0]->var);
        default:
          break;
      }
    }
    switch (n.op) {
      case Op::Add:
      case Op::Sub: {
        v.mean = plain(n, a);
        if (ca || cb) return Val{v.mean, ca ? a[1]->var : a[0]->var, ca ? a[1]->sd : a[0]->sd};
        if (rho_zero(r) && shared_rho(n) < 0) {
          v.var = add(a[0]->var, a[1]->var);
          return v;
        }
        int cov = mul(mul(k(2), rho(i, n, r)), mul(sd(*a[0]), sd(*a[1])));
        if (n.op == Op::Sub) cov = op(LOp::Neg, cov);
        v.var = op(LOp::NonNeg, add(add(a[0]->var, a[1]->var), cov));
        return v;
      }
      case Op::Mul:
        if (ca || cb) {  // product with a non-random factor: exact
          v.mean = plain(n, a);
          v.var = ca ? mul(sq(a[0]->mean), a[1]->var) : mul(sq(a[1]->mean), a[0]->var);
          return v;
        }
        if (rho_zero(r) && shared_rho(n) < 0) {
          // Independent factors (bivariate::mul at rho 0, inlined): the mean reads no variance, so
          // a variance only this product's variance reads is dead when nothing reads that one.
          v.mean = plain(n, a);
          v.var = add(add(mul(a[0]->var, a[1]->var), mul(sq(a[0]->mean), a[1]->var)),
                      mul(sq(a[1]->mean), a[0]->var));
          return v;
        }
        break;
      case Op::Div:
        if (cb) {
          v.mean = plain(n, a);
          v.var = div(a[0]->var, sq(a[1]->mean));
          return v;
        }
        break;
      case Op::Select:
        return from_stat(call("bl::bivariate::select",
                              {a[0]->mean, sd(*a[0]), a[1]->mean, sd(*a[1]), a[2]->mean, sd(*a[2])}, true));
      case Op::Mod:
        if (r.kind == Kind::Gaussian && facts_.cell_continuous(n.a, n.value)) {
          // mod(x, P) = P fract(x / P) where the output hides its jumps: fract's mode, as for a fract
          // node (a hexagonal tiling's mod(p, s) - s / 2 under |.|; with the full rule its seams
          // read a mean of both sides and drew grout lines across the tiles).
          const float c = static_cast<float>(n.value), inv = 1.0f / c;
          const Val f = mode_fract(mul(a[0]->mean, k(inv)), mul(scaled_sd(*a[0], r), k(std::fabs(inv))));
          return Val{mul(k(c), f.mean), mul(k(c * c), f.var)};
        }
        return from_stat(call("bl::bivariate::mod",
                              {a[0]->mean, scaled_sd(*a[0], r), k(static_cast<float>(n.value))}, true));
      default:
        break;
    }
    const std::string name = std::string("bl::bivariate::") + ir::op_name(n.op);
    return from_stat(call(name, {a[0]->mean, sd(*a[0]), a[1]->mean, sd(*a[1]), rho(i, n, r)}, true));
  }

  // d/dm of the node's smoothed mean (for a smoothing rule; the plain f' for none or a non-random
  // input). By Stein's lemma E[f'(X)] = d/dm E[f(X)], so for a jump (step, square, fract) the slope is
  // the kernel's density at the jump, not the plain derivative's 0: two values that jump together
  // (zigzag's hue and band) then get correlated gradients. Central difference at h = s/2.
  int smoothed_slope(int i, const ir::Node& n) {
    const std::string f = ir::atomic_name(n.atomic);
    Val& x = vals_[n.a];
    const Rule& r = s_.at(i);
    if (r.kind == Kind::None || r.kind == Kind::MonteCarlo || x.var < 0)
      return call("bl::deriv::" + f + "_d1", {x.mean});
    // A fract reported as one side of its jump (mode_fract) has slope 1 there, not the jump's.
    if (r.kind == Kind::Gaussian && fract_takes_mode(i)) return k(1);
    const std::string kern = kernel_name(kernel_for("gaussian", f), f, false);
    const int s = scaled_sd(x, r), h = add(mul(k(0.5f), s), k(1e-4f));
    return div(sub(call(kern, {add(x.mean, h), s}), call(kern, {sub(x.mean, h), s})), mul(k(2), h));
  }

  // Screen-space gradient of node i's mean (forward mode through the plain derivatives at the
  // means: the affine assumption of Yang & Barnes, Appendix B).
  Val& grad(int i) {
    Val& v = vals_[i];
    if (v.gx >= 0) return v;
    const ir::Node& n = g_.node(i);
    auto set = [&](int gx, int gy) {
      v.gx = gx;
      v.gy = gy;
    };
    auto G = [&](int j) -> Val& { return grad(j); };
    switch (n.op) {
      case Op::Const:
        set(k(0), k(0));
        break;
      case Op::Input: {
        const int slot = static_cast<int>(n.value);
        if (!g_.inputs()[slot].varying) {
          set(k(0), k(0));
          break;
        }
        const int gx = input(LOp::InGradX, slot);
        set(gx, input(LOp::InGradY, slot));
        break;
      }
      case Op::Add:
        set(add(G(n.a).gx, G(n.b).gx), add(G(n.a).gy, G(n.b).gy));
        break;
      case Op::Sub:
        set(sub(G(n.a).gx, G(n.b).gx), sub(G(n.a).gy, G(n.b).gy));
        break;
      case Op::Neg:
        set(op(LOp::Neg, G(n.a).gx), op(LOp::Neg, G(n.a).gy));
        break;
      case Op::Mod:
        set(G(n.a).gx, G(n.a).gy);
        break;
      case Op::Less: {
        // Smoothed less(a, b) = Phi((mb - ma) / s): its slope in mb - ma (Stein's lemma) is the
        // Gaussian density there, where the plain derivative is 0 almost everywhere.
        Val &a = vals_[n.a], &b = vals_[n.b];
        if (s_.at(i).kind == Kind::None || (a.var < 0 && b.var < 0)) {
          set(k(0), k(0));
          break;
        }
        const int va = a.var < 0 ? k(0) : a.var, vb = b.var < 0 ? k(0) : b.var;
        const int sab = op(LOp::Sqrt, op(LOp::Max, add(va, vb), k(1e-30f)));
        const int x = sub(b.mean, a.mean), h = add(mul(k(0.5f), sab), k(1e-4f));
        const std::string st = kernel_name("gaussian", "step", false);
        const int fp = div(sub(call(st, {add(x, h), sab}), call(st, {sub(x, h), sab})), mul(k(2), h));
        set(mul(fp, sub(G(n.b).gx, G(n.a).gx)), mul(fp, sub(G(n.b).gy, G(n.a).gy)));
        break;
      }
      // Texels are treated as uncorrelated with the shader's other values (no derivative of a
      // discrete function): a rho=grad product with a texture value gets rho 0.
      case Op::Texture:
        set(k(0), k(0));
        break;
      case Op::Mul: {
        const int ma = vals_[n.a].mean, mb = vals_[n.b].mean;
        set(add(mul(ma, G(n.b).gx), mul(mb, G(n.a).gx)), add(mul(ma, G(n.b).gy), mul(mb, G(n.a).gy)));
        break;
      }
      case Op::Div: {
        const int ma = vals_[n.a].mean, mb = vals_[n.b].mean, d = sq(mb);
        set(div(sub(mul(G(n.a).gx, mb), mul(ma, G(n.b).gx)), d),
            div(sub(mul(G(n.a).gy, mb), mul(ma, G(n.b).gy)), d));
        break;
      }
      case Op::Min:
      case Op::Max: {
        const int ma = vals_[n.a].mean, mb = vals_[n.b].mean;
        const int pick_a = n.op == Op::Min ? op(LOp::Less, ma, mb) : op(LOp::Less, mb, ma);
        const int pick_b = sub(k(1), pick_a);
        set(add(mul(pick_a, G(n.a).gx), mul(pick_b, G(n.b).gx)),
            add(mul(pick_a, G(n.a).gy), mul(pick_b, G(n.b).gy)));
        break;
      }
      case Op::Select: {
        const int mc = vals_[n.a].mean, d = sub(vals_[n.b].mean, vals_[n.c].mean), nc = sub(k(1), mc);
        set(add(mul(G(n.a).gx, d), add(mul(mc, G(n.b).gx), mul(nc, G(n.c).gx))),
            add(mul(G(n.a).gy, d), add(mul(mc, G(n.b).gy), mul(nc, G(n.c).gy))));
        break;
      }
      case Op::Call: {
        const int fp = smoothed_slope(i, n);
        set(mul(fp, G(n.a).gx), mul(fp, G(n.a).gy));
        break;
      }
    }
    return vals_[i];
  }

  // d E[node] / d E[root]: beta through affine steps, the atomics' Stein slopes (smoothed_slope).
  int root_slope(int i) {
    if (slope_[i] >= 0) return slope_[i];
    const ir::Node& n = g_.node(i);
    int sl;
    if (facts_.aff[i].base >= 0 && facts_.aff[i].base != i)
      sl = mul(k(static_cast<float>(facts_.aff[i].beta)), root_slope(facts_.aff[i].base));
    else if (n.op == Op::Call)
      sl = mul(smoothed_slope(i, n), root_slope(n.a));
    else
      sl = k(1);
    return slope_[i] = sl;
  }
  // InGradX and InGradY of input node i.
  std::pair<int, int> input_gradient(int i) {
    const int slot = static_cast<int>(g_.node(i).value), gx = input(LOp::InGradX, slot);
    return {gx, input(LOp::InGradY, slot)};
  }

  // The correlation of binary node n's operands when the rule says rho 0 but the graph knows
  // better, or -1 (none known: independent). Affine functions of one base node are perfectly
  // correlated (+-1); functions of one root node R (zigzag's hue and band, both of y) get
  // Cov ~ Var(R) E[A'(R)] E[B'(R)] (Stein's lemma, exact when one of them is affine in R).
  int shared_rho(const ir::Node& n) {
    if (n.b < 0 || n.a == n.b) return -1;
    const Affine &a = facts_.aff[n.a], &b = facts_.aff[n.b];
    if (a.base >= 0 && a.base == b.base && a.beta != 0 && b.beta != 0)
      return k(a.beta * b.beta > 0 ? 1.0f : -1.0f);
    if (vals_[n.a].var < 0 || vals_[n.b].var < 0) return -1;
    const int ra = facts_.root[n.a], rb = facts_.root[n.b];
    if (vals_[ra].var < 0 || vals_[rb].var < 0) return -1;
    int cov;
    if (ra == rb) {
      cov = mul(vals_[ra].var, mul(root_slope(n.a), root_slope(n.b)));
    } else if (g_.node(ra).op == Op::Input && g_.node(rb).op == Op::Input) {
      // Functions of two surface coordinates: u and v are affine in screen space over a pixel, so
      // their correlation is the normalised dot product of their screen gradients (exact for the
      // isotropic pixel Gaussian); the footprint of a rotated view correlates them.
      const auto ga = input_gradient(ra), gb = input_gradient(rb);
      const int dot = add(mul(ga.first, gb.first), mul(ga.second, gb.second));
      const int na = add(sq(ga.first), sq(ga.second)), nb = add(sq(gb.first), sq(gb.second));
      const int ruv = div(dot, op(LOp::Sqrt, op(LOp::Max, mul(na, nb), k(1e-30f))));
      cov = mul(mul(ruv, mul(sd(vals_[ra]), sd(vals_[rb]))), mul(root_slope(n.a), root_slope(n.b)));
    } else {
      return -1;
    }
    const int den = op(LOp::Max, mul(sd(vals_[n.a]), sd(vals_[n.b])), k(1e-30f));
    return op(LOp::Min, op(LOp::Max, div(cov, den), k(-1)), k(1));
  }

  // ---- Bernoulli mixtures: selects keep their two lobes apart ----
  // A select whose condition c = less(a, b) is random mixes two branches; its (mean, variance) pair
  // merges them into one lobe (bumps: the cap's normals and the flat (0,0,1) averaged into one mean
  // normal before dot/reflect/pow8). Here c is a Bernoulli node with p = the smoothed less (its own
  // rule's mean): every node downstream of c is lowered once with c = 1 and once with c = 0 (the
  // selects then pass their branch on) and the outputs are mixed, p A + (1 - p) B (mean and second
  // moment). Where c compares a random node x with a non-random one, the branch also conditions x on
  // its side (truncated-normal moments) and re-lowers the nodes between x and the selects' values
  // (a cap's height sqrt(saturate(R^2 - r2)) given r2 < R^2). Joint over the first kMaxJoint
  // comparisons an output depends on (treated as independent): 2^kMaxJoint branches.
  static constexpr int kMaxJoint = 2;
  static constexpr int kBothSides = -2;  // operand of a comparison whose two sides are both conditioned

  bool bernoulli(int i) const {
    const Kind kd = s_.at(i).kind;
    return kd != Kind::None && kd != Kind::MonteCarlo && vals_[i].var >= 0 && facts_.select_condition(i);
  }

  // x ~ N(m, s^2) (its lowered moments) conditioned on x < t (upper) or x >= t: the truncated
  // normal's mean m -+ s lambda and variance s^2 (1 -+ alpha lambda - lambda^2), alpha = (t - m) / s,
  // lambda = phi(alpha) / P(side). lambda is finite where P underflows (phi does too: lambda 0, and the
  // branch has weight ~0 anyway).
  Val truncated(Val& x, int t, bool upper) {
    const int s = sd(x);
    const int alpha = div(sub(t, x.mean), op(LOp::Max, s, k(1e-30f)));
    const int phi = mul(k(0.3989422804f), call(plain_name("exp"), {mul(k(-0.5f), sq(alpha))}));
    const std::string step = kernel_name("gaussian", "step", false);
    const int side = upper ? call(step, {sub(t, x.mean), s}) : call(step, {sub(x.mean, t), s});
    const int lambda = div(phi, op(LOp::Max, side, k(1e-30f)));
    Val v;
    v.mean = upper ? sub(x.mean, mul(s, lambda)) : add(x.mean, mul(s, lambda));
    const int al = mul(alpha, lambda);
    v.var = op(LOp::NonNeg, mul(x.var, sub(upper ? sub(k(1), al) : add(k(1), al), sq(lambda))));
    return v;
  }

  // Side x of comparison c = less(a, b) fixed to `bit` against the other side's value t: c = 1 is
  // a < b (a truncated above at t, or b below at t), c = 0 the other way; its mean kept inside x's
  // range (a squared distance truncated below its threshold can have a Gaussian mean below 0).
  Val side_of(int c, int x, int t, int bit) {
    return in_range(x, truncated(vals_[x], t, (x == g_.node(c).a) == (bit == 1)));
  }

  // The candidate side of a cascade link's comparison (d in `d < best` or `best > d`): the side that
  // is not the running value, a select of the links below.
  int candidate(int c) const {
    const ir::Node& n = g_.node(c);
    return g_.node(n.a).op == Op::Select ? n.b : n.a;
  }

  // Comparison c = less(a, b) with both sides random, fixed to a < b (below) or a >= b: z = a - b
  // (a and b taken independent) is truncated at 0, and each side regressed on z (the Gaussian
  // conditional: mean shift var_side / var_z of z's, variance drop by the share z's variance lost).
  // A cascade's winner x_j < best: without it the branch kept the footprint where x_j loses, and
  // Voronoi's border term sqrt(second) - sqrt(best) went negative there (borders too dark). The
  // sides alone take the moments (held), not their sources as condition() does: conditioning d_j's
  // sources too changed no error on Voronoi or the test and re-lowered 460 more instructions.
  void condition_both(int c, bool below, std::set<int>& held) {
    const ir::Node& n = g_.node(c);
    Val z;
    z.mean = sub(vals_[n.a].mean, vals_[n.b].mean);
    z.var = add(vals_[n.a].var, vals_[n.b].var);
    const Val zt = truncated(z, k(0), below);
    const int vz = op(LOp::Max, z.var, k(1e-30f));
    const int dm = sub(zt.mean, z.mean), lost = sub(k(1), div(zt.var, vz));
    const Val a = vals_[n.a], b = vals_[n.b];
    for (const auto& [side, x] : {std::pair{n.a, a}, std::pair{n.b, b}}) {
      const int f = div(x.var, vz);  // b enters z negated
      Val v;
      v.mean = side == n.a ? add(x.mean, mul(f, dm)) : sub(x.mean, mul(f, dm));
      v.var = op(LOp::NonNeg, sub(x.var, mul(mul(f, x.var), lost)));
      vals_[side] = in_range(side, v);  // (a regressed squared distance can fall below 0)
      held.insert(side);
    }
  }

  // Node x takes the branch's moments v: its sources are conditioned back along sums (independent
  // addends share a mean shift and a variance drop in proportion to their variances: the Gaussian
  // regression), constant affine steps (inverted) and squares (y scaled about 0 so that E[y^2]
  // matches: a disk r2 = fu^2 + fv^2 < R^2 narrows fu and fv, which linear regression on r2 cannot
  // see at a mean of 0). held collects the nodes given moments this way (not re-lowered).
  void condition(int x, Val v, std::set<int>& held, int depth = 0) {
    Val old = vals_[x];
    vals_[x] = v;
    held.insert(x);
    if (depth > 8 || old.var < 0) return;
    const ir::Node& n = g_.node(x);
    auto cst = [&](int j) { return j >= 0 && vals_[j].var < 0; };
    const int dm = sub(v.mean, old.mean);
    auto var_or0 = [&](const Val& a) { return a.var < 0 ? k(0) : a.var; };
    switch (n.op) {
      case Op::Add:
      case Op::Sub:
        if (n.a == n.b) return;
        if (cst(n.a) || cst(n.b)) {
          const int y = cst(n.a) ? n.b : n.a;
          const bool neg = n.op == Op::Sub && y == n.b;
          Val w;
          w.mean = add(vals_[y].mean, neg ? op(LOp::Neg, dm) : dm);
          w.var = v.var;
          condition(y, w, held, depth + 1);
          return;
        }
        {
          const int va = var_or0(vals_[n.a]), vb = var_or0(vals_[n.b]);
          const int tot = op(LOp::Max, add(va, vb), k(1e-30f));
          const int drop = op(LOp::Max, sub(var_or0(old), var_or0(v)), k(0));
          for (int j : {n.a, n.b}) {
            const int f = div(j == n.a ? va : vb, tot);
            const bool neg = n.op == Op::Sub && j == n.b;
            Val w;
            w.mean = add(vals_[j].mean, mul(neg ? op(LOp::Neg, f) : f, dm));
            w.var = op(LOp::NonNeg, sub(var_or0(vals_[j]), mul(sq(f), drop)));
            condition(j, w, held, depth + 1);
          }
        }
        return;
      case Op::Neg: {
        Val w{op(LOp::Neg, v.mean), v.var};
        condition(n.a, w, held, depth + 1);
        return;
      }
      case Op::Mul:
        if (n.a == n.b || (n.op == Op::Mul && facts_.monomial(x) == std::make_pair(n.a, 2))) break;
        if (cst(n.a) || cst(n.b)) {
          const int y = cst(n.a) ? n.b : n.a, c = vals_[cst(n.a) ? n.a : n.b].mean;
          Val w{div(v.mean, c), div(var_or0(v), sq(c))};
          condition(y, w, held, depth + 1);
        }
        return;
      case Op::Call:
        if (std::string(ir::atomic_name(n.atomic)) == "pow2") break;
        return;
      default:
        return;
    }
    // x = y^2: y scaled about 0 by sqrt(E[x | branch] / E[x]).
    const int y = n.a;
    const int sc = op(LOp::Sqrt, div(op(LOp::NonNeg, v.mean), op(LOp::Max, old.mean, k(1e-30f))));
    Val w{mul(vals_[y].mean, sc), mul(var_or0(vals_[y]), sq(sc))};
    condition(y, w, held, depth + 1);
  }

  // What a group of outputs mixes over: comparisons (bern indices). A cascade's first pass.size()
  // are its links, top first, with the value of each that passes down, and any after them are mixed
  // jointly with its outcomes; with pass empty, every combination of them.
  struct Mix {
    std::vector<int> set, pass;
    bool operator<(const Mix& o) const { return std::tie(set, pass) < std::tie(o.set, o.pass); }
  };
  // The select cascade (GraphFacts::cascade) output o mixes over; empty when o reads none of at
  // least kMinCascade links. Among several, the one whose every condition the
  // most selects share, then the longest: Voronoi's nearest distance and nearest cell (hence its
  // colour) follow the `d < best` conditions; the second nearest's chain interleaves conditions only
  // it reads, and mixing over it would leave the nearest cell unresolved in half its branches.
  static constexpr std::size_t kMinCascade = kMaxJoint + 1;
  Mix output_cascade(int o, const std::vector<int>& where) const {
    std::vector<bool> anc(g_.size(), false);
    anc[o] = true;
    for (int x = o; x >= 0; --x)
      if (anc[x])
        for (int a : {g_.node(x).a, g_.node(x).b, g_.node(x).c})
          if (a >= 0) anc[a] = true;
    auto is_cond = [&](int c) { return c >= 0 && where[c] >= 0; };
    std::vector<GraphFacts::Link> best;
    int best_share = 0;
    for (int s = o; s >= 0; --s) {
      if (!anc[s] || g_.node(s).op != Op::Select || !is_cond(g_.node(s).a)) continue;
      const std::vector<GraphFacts::Link> links = facts_.cascade(s, is_cond);
      if (links.size() < kMinCascade) continue;
      int share = g_.size();
      for (const auto& l : links) share = std::min(share, facts_.selects_reading(l.cond));
      if (share > best_share || (share == best_share && links.size() > best.size())) {
        best = links;
        best_share = share;
      }
    }
    Mix mix;
    for (const auto& l : best) {
      mix.set.push_back(where[l.cond]);
      mix.pass.push_back(l.pass);
    }
    return mix;
  }

  void bernoulli_mixtures() {
    std::vector<int> bern;
    for (int i = 0; i < g_.size(); ++i)
      if (bernoulli(i)) bern.push_back(i);
    if (bern.empty()) return;
    std::vector<std::vector<bool>> desc;
    for (int c : bern) desc.push_back(facts_.descendants(c));
    // Outputs grouped by the branches they mix: the outcomes of the select cascade they read (the
    // last condition that holds picks the value: n + 1 branches, the conditions below the winner left
    // to their rules), else every combination of the first kMaxJoint comparisons they depend on.
    std::map<Mix, std::vector<int>> groups;  // -> output nodes
    std::vector<int> where(g_.size(), -1);   // node -> its index in bern
    for (std::size_t b = 0; b < bern.size(); ++b) where[bern[b]] = static_cast<int>(b);
    for (int o : g_.outputs()) {
      Mix mix = output_cascade(o, where);
      std::vector<int>& set = mix.set;
      if (!set.empty()) {
        // Beside the cascade, the first other comparison that picks a vector (several selects read
        // it: a bump's cap or flat normal) stays joint with it.
        for (std::size_t b = 0; b < bern.size(); ++b)
          if (desc[b][o] && facts_.selects_reading(bern[b]) >= 2 &&
              std::find(set.begin(), set.end(), static_cast<int>(b)) == set.end()) {
            set.push_back(static_cast<int>(b));
            break;
          }
      }
      if (set.empty()) {
        for (std::size_t b = 0; b < bern.size() && static_cast<int>(set.size()) < kMaxJoint; ++b)
          if (desc[b][o]) set.push_back(static_cast<int>(b));
      }
      if (set.empty()) continue;
      auto& outs = groups[mix];
      if (std::find(outs.begin(), outs.end(), o) == outs.end()) outs.push_back(o);  // r = g = b for grey
    }
    std::map<int, Val> mixed;
    for (const auto& [mix, outs] : groups) {
      const std::vector<int>& set = mix.set;
      const std::vector<int>& pass = mix.pass;
      // The conditioned operand of each comparison (-1: none) and the nodes each branch re-lowers.
      std::vector<int> operand(set.size(), -1);
      std::vector<bool> redo(g_.size(), false);
      for (std::size_t j = 0; j < set.size(); ++j) {
        const int c = bern[set[j]];
        const ir::Node& n = g_.node(c);
        const bool ra = vals_[n.a].var >= 0, rb = vals_[n.b].var >= 0;
        if (ra != rb) operand[j] = ra ? n.a : n.b;
        if (ra && rb && j < pass.size()) operand[j] = kBothSides;  // a cascade link: x_j < best
        for (int x = 0; x < g_.size(); ++x) redo[x] = redo[x] || desc[set[j]][x];
        if (operand[j] >= 0) {
          // Everything between the operand's sources and the selects' values.
          const std::vector<bool> anc = facts_.branch_ancestors(c);
          std::vector<bool> up(g_.size(), false);  // the operand and its ancestors
          up[operand[j]] = true;
          for (int x = operand[j]; x >= 0; --x)
            if (up[x])
              for (int a : {g_.node(x).a, g_.node(x).b, g_.node(x).c})
                if (a >= 0) up[a] = true;
          std::vector<bool> below(g_.size(), false);  // descendants of the operand's ancestors
          for (int x = 0; x < g_.size(); ++x) {
            below[x] = up[x];
            for (int a : {g_.node(x).a, g_.node(x).b, g_.node(x).c})
              if (a >= 0 && below[a]) below[x] = true;
          }
          for (int x = 0; x < g_.size(); ++x) redo[x] = redo[x] || (below[x] && anc[x]);
        }
      }
      std::vector<int> p(set.size());
      for (std::size_t j = 0; j < set.size(); ++j)
        p[j] = call(plain_name("saturate"), {vals_[bern[set[j]]].mean});
      std::map<int, int> sum_m, sum_m2;  // output node -> instruction
      const std::vector<Val> base = vals_;
      const std::vector<int> base_slope = slope_;
      // Per branch, per comparison of the set: the value it is fixed to (-1: left to its rule).
      std::vector<std::vector<int>> branches;
      if (!pass.empty()) {
        // Outcome j: links above j pass x down, link j takes its A; outcome n: every link passes.
        const std::size_t n = pass.size(), extra = set.size() - n;
        for (std::size_t j = 0; j <= n; ++j)
          for (int mask = 0; mask < (1 << extra); ++mask) {
            std::vector<int> bits(set.size(), -1);
            for (std::size_t l = 0; l < n && l <= j; ++l) bits[l] = l < j ? pass[l] : 1 - pass[l];
            for (std::size_t e = 0; e < extra; ++e) bits[n + e] = (mask >> e) & 1;
            branches.push_back(bits);
          }
      } else {
        for (int mask = 0; mask < (1 << set.size()); ++mask) {
          std::vector<int> bits(set.size());
          for (std::size_t j = 0; j < set.size(); ++j) bits[j] = (mask >> j) & 1;
          branches.push_back(bits);
        }
      }
      for (const std::vector<int>& bits : branches) {
        int w = -1;
        std::set<int> held;
        std::vector<std::size_t> passing;  // cascade links above the winner, conditioned after it
        int winner = -1;                   // the winning link's x_j (conditioned)
        for (std::size_t j = 0; j < set.size(); ++j) {
          const int c = bern[set[j]], bit = bits[j];
          if (bit < 0) continue;
          fixed_[c] = bit;
          w = w < 0 ? (bit ? p[j] : sub(k(1), p[j])) : mul(w, bit ? p[j] : sub(k(1), p[j]));
          if (operand[j] == kBothSides) {
            if (bit == pass[j]) {
              passing.push_back(j);
            } else {
              winner = candidate(c);
              condition_both(c, bit == 1, held);
            }
            continue;
          }
          if (operand[j] < 0) continue;
          const ir::Node& n = g_.node(c);
          const int t = vals_[operand[j] == n.a ? n.b : n.a].mean;
          condition(operand[j], side_of(c, operand[j], t, bit), held);
        }
        // A link above the winner passes: its x_l >= best, which is the winner's x_j in this branch.
        for (std::size_t j : passing) {
          const int c = bern[set[j]], x = candidate(c);
          if (winner >= 0 && !held.count(x)) {
            vals_[x] = side_of(c, x, vals_[winner].mean, bits[j]);
            held.insert(x);
          }
        }
        set_branch_lattice();
        for (int x = 0; x < g_.size(); ++x)
          if (redo[x] && !held.count(x)) {
            slope_[x] = -1;
            vals_[x] = node(x);
          }
        branch_lattice_.clear();
        for (int o : outs) {
          Val& v = vals_[o];
          const int m2 = v.var < 0 ? sq(v.mean) : add(v.var, sq(v.mean));
          sum_m[o] = sum_m.count(o) ? add(sum_m[o], mul(w, v.mean)) : mul(w, v.mean);
          sum_m2[o] = sum_m2.count(o) ? add(sum_m2[o], mul(w, m2)) : mul(w, m2);
        }
        vals_ = base;
        slope_ = base_slope;
        fixed_.clear();
      }
      for (int o : outs) {
        Val v;
        v.mean = sum_m[o];
        v.var = op(LOp::NonNeg, sub(sum_m2[o], sq(v.mean)));
        mixed[o] = v;
      }
    }
    for (const auto& [o, v] : mixed) vals_[o] = v;
  }

  // A lattice node as the finite mixture over its sources' values (GraphFacts::Lattice): floor/ceil
  // of N(m, s^2) is K-1, K or K+1 with Gaussian interval probabilities; the plain sub-DAG per pair.
  Val lattice_mixture(int i, const Rule& r) {
    const std::vector<int> src = lattices()[i].src;
    struct Choice {
      std::vector<int> value, weight;  // instruction per candidate
    };
    std::vector<Choice> ch(src.size());
    const std::string step = kernel_name("gaussian", "step", false);
    for (std::size_t d = 0; d < src.size(); ++d) {
      const ir::Node& fl = g_.node(src[d]);
      const bool is_floor = std::string(ir::atomic_name(fl.atomic)) == "floor";
      Val& x = vals_[fl.a];
      const int K = call(plain_name(is_floor ? "floor" : "ceil"), {x.mean});
      const int s = x.var < 0 ? k(0) : scaled_sd(x, r);
      for (int o = -1; o <= 1; ++o) {
        const int v = add(K, k(static_cast<float>(o)));
        // floor = v on [v, v + 1); ceil = v on (v - 1, v]: P = Phi((hi - m)/s) - Phi((lo - m)/s).
        const int lo = is_floor ? v : sub(v, k(1)), hi = is_floor ? add(v, k(1)) : v;
        int p = sub(call(step, {sub(hi, x.mean), s}), call(step, {sub(lo, x.mean), s}));
        if (facts_.cell_continuous(fl.a)) {
          // The output does not jump where this floor does: take the cell holding m (as mode_fract
          // takes the side holding m), blended into the probabilities as s grows.
          const int t = mode_blend(s);
          p = add(mul(t, p), o == 0 ? sub(k(1), t) : k(0));
        }
        ch[d].value.push_back(v);
        ch[d].weight.push_back(p);
      }
    }
    const GraphFacts::LatticeMoments far = facts_.lattice_moments(i, fixed_, lattices());
    // A cheaper rule than the Gaussian on a node whose cells' edges the output hides: the cell of the
    // mean alone, the rest of the mass at the lattice average (one evaluation instead of 3 or 9:
    // exact while the footprint is within a quarter cell, the average for a wide one, coarser
    // between).
    bool one_cell = r.kind != Kind::Gaussian && far.ok;
    for (int d : src) one_cell = one_cell && facts_.cell_continuous(g_.node(d).a);
    int sum_w = -1, sum_h = -1;
    std::vector<int> ws, hs;
    const int combos = src.size() == 1 ? 3 : 9, centre = src.size() == 1 ? 1 : 4;
    for (int c = 0; c < combos; ++c) {
      if (one_cell && c != centre) continue;
      std::map<int, int> memo;
      int w = -1;
      for (std::size_t d = 0; d < src.size(); ++d) {
        const int pick = d == 0 ? c % 3 : c / 3;
        memo[src[d]] = ch[d].value[pick];
        w = w < 0 ? ch[d].weight[pick] : mul(w, ch[d].weight[pick]);
      }
      const int h = lattice_eval(i, memo);
      sum_w = sum_w < 0 ? w : add(sum_w, w);
      sum_h = sum_h < 0 ? mul(w, h) : add(sum_h, mul(w, h));
      ws.push_back(w);
      hs.push_back(h);
    }
    Val v;
    // Centred second moments below: E[h^2] - mean^2 cancels in float (at h ~ 7e4 to an error of
    // ~300, and the next rule's e^{-var/2} wipes a sine of h out); sum w (h - mean)^2 is exactly 0
    // where one cell has all the weight.
    auto centred = [&](int mean) {
      int d2 = -1;
      for (std::size_t c = 0; c < hs.size(); ++c) {
        const int t = mul(ws[c], sq(sub(hs[c], mean)));
        d2 = d2 < 0 ? t : add(d2, t);
      }
      return d2;
    };
    if (far.ok) {
      // The cells beyond K +- 1 (a footprint wider than a cell) hold the rest of the mass, 1 - sum w:
      // they take the node's mean and variance over the whole lattice, so a wide footprint tends to
      // the pattern's average instead of renormalising three cells (noise in the far field).
      const int rest = op(LOp::Max, sub(k(1), sum_w), k(0));
      const int gm = k(static_cast<float>(far.mean));
      v.mean = add(sum_h, mul(rest, gm));
      v.var = add(centred(v.mean), mul(rest, add(k(static_cast<float>(far.var)), sq(sub(gm, v.mean)))));
      return v;
    }
    const int inv = div(k(1), op(LOp::Max, sum_w, k(1e-30f)));
    v.mean = mul(sum_h, inv);
    v.var = mul(centred(v.mean), inv);
    return v;
  }
  // The plain value of lattice node i with its sources fixed (memo: node -> instruction); in a
  // mixture branch, through the selects and comparisons it fixes.
  int lattice_eval(int i, std::map<int, int>& memo) {
    auto it = memo.find(i);
    if (it != memo.end()) return it->second;
    const ir::Node& n = g_.node(i);
    int out;
    const int p = GraphFacts::passed(n, fixed_);
    if (const auto f = fixed_.find(i); f != fixed_.end()) {
      out = k(static_cast<float>(f->second));
    } else if (p >= 0) {
      out = lattice_eval(p, memo);
    } else if (n.op == Op::Const) {
      out = k(static_cast<float>(n.value));
    } else {
      std::vector<int> x;
      for (int a : {n.a, n.b, n.c})
        if (a >= 0) x.push_back(lattice_eval(a, memo));
      out = plain(n, x);
    }
    return memo[i] = out;
  }

  const ir::Graph& g_;
  const Schedule& s_;
  std::vector<Val> vals_;
  std::vector<ir::Interval> ranges_;  // plain value ranges (ir/ranges.hpp): Dorn's means stay inside
  Program p_;
  std::set<std::string> notes_;
  GraphFacts facts_;
  PeriodicFarField far_;
  std::vector<char> exact_;  // per node: exact_linear or a fused exact rule (node())
  // Per node: root_slope's instruction (-1: not yet).
  std::vector<int> slope_;
  // While a Bernoulli mixture lowers one branch: comparison node -> its value (0 or 1).
  std::map<int, int> fixed_;
  // The lattice facts in that branch (empty outside one): set_branch_lattice.
  std::vector<Lattice> branch_lattice_;

  // A fixed select is the branch it passes on and a fixed comparison a constant, so in a branch the
  // hash of the cell a cascade picks (Voronoi's colour of the nearest cell) is a lattice function:
  // evaluated plain per cell instead of smoothed (a hash's gain turns any spread of its argument,
  // or any difference in rounding from the plain shader, into noise).
  void set_branch_lattice() {
    branch_lattice_.assign(g_.size(), Lattice{});
    for (int x = 0; x < g_.size(); ++x) {
      const int p = GraphFacts::passed(g_.node(x), fixed_);
      if (fixed_.count(x))
        branch_lattice_[x] = Lattice{true, {}};
      else if (p >= 0)
        branch_lattice_[x] = branch_lattice_[p];
      else
        branch_lattice_[x] = facts_.lattice_sources_from(x, branch_lattice_);
    }
  }
  const std::vector<Lattice>& lattices() const {
    return branch_lattice_.empty() ? facts_.lattice : branch_lattice_;
  }
  bool lattice_boundary(int i) const { return facts_.lattice_boundary_in(i, lattices()); }
};

}  // namespace

namespace {

void check_schedule(const ir::Graph& g, const Schedule& schedule) {
  if (static_cast<int>(schedule.size()) != g.size())
    throw std::invalid_argument("compiler: schedule has " + std::to_string(schedule.size()) +
                                " rules for a graph of " + std::to_string(g.size()) + " nodes");
  for (const auto& n : g.nodes())
    if (n.op == ir::Op::Const && !std::isfinite(n.value))
      throw std::invalid_argument("compiler: the shader has a non-finite constant");
}

}  // namespace

Program lower(const ir::Graph& g, const Schedule& schedule) {
  check_schedule(g, schedule);
  return Lowering(g, schedule).run();
}

Program lower_naive(const ir::Graph& g, const Schedule& schedule) {
  check_schedule(g, schedule);
  return Lowering(g, schedule).run_naive();
}

Schedule uniform_schedule(const ir::Graph& g, const rules::Rule& r) {
  return Schedule(g.size(), r);
}

std::vector<float> mc_normals(int node, int n, int dims) {
  // Seeded per node so that a node's samples do not depend on the rest of the shader.
  std::mt19937_64 rng(0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(node) * 0x100000001B3ull);
  std::normal_distribution<double> normal;
  std::vector<float> z(static_cast<std::size_t>(n) * dims);
  std::vector<double> raw(z.size());
  for (int j = 0; j + 1 < n; j += 2)
    for (int d = 0; d < dims; ++d) {
      const double v = normal(rng);
      raw[j * dims + d] = v;
      raw[(j + 1) * dims + d] = -v;
    }
  // Moment matching: scale each dimension to unit mean square, so the samples carry the input's
  // full variance (8 raw draws can have an RMS of 0.5: the node would smooth with half its sd).
  for (int d = 0; d < dims; ++d) {
    double ms = 0;
    for (int j = 0; j < n; ++j) ms += raw[j * dims + d] * raw[j * dims + d];
    const double scale = ms > 0 ? 1 / std::sqrt(ms / n) : 0;
    for (int j = 0; j < n; ++j) z[j * dims + d] = static_cast<float>(raw[j * dims + d] * scale);
  }
  return z;
}

}  // namespace bl::compiler
