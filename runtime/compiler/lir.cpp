#include "compiler/lir.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <tuple>

namespace bl::compiler {

bool Inst::operator==(const Inst& o) const {
  return op == o.op && fn == o.fn && tex == o.tex && channel == o.channel &&
         std::memcmp(&k, &o.k, sizeof k) == 0 &&
         std::equal(std::begin(arg), std::end(arg), std::begin(o.arg));
}

int lop_arity(const Inst& in) {
  switch (in.op) {
    case LOp::Const:
    case LOp::InMean:
    case LOp::InSd:
    case LOp::InGradX:
    case LOp::InGradY:
      return 0;  // arg[0] of In* is a slot, not an instruction
    case LOp::Neg:
    case LOp::Sqrt:
    case LOp::NonNeg:
    case LOp::Mean:
    case LOp::Var:
      return 1;
    case LOp::Call:
    case LOp::CallStat:
      return functions()[in.fn].arity;
    case LOp::TexStat:
      return 4;
    default:
      return 2;
  }
}

bool Program::uses_gradients() const {
  for (const Inst& in : insts)
    if (in.op == LOp::InGradX || in.op == LOp::InGradY) return true;
  return false;
}

Program Program::interface_only() const {
  Program out;
  out.input_count = input_count;
  out.input_names = input_names;
  out.output_names = output_names;
  out.texture_names = texture_names;
  out.notes = notes;
  return out;
}

std::vector<int> Program::used_functions() const {
  std::set<int> s;
  for (const Inst& in : insts)
    if (in.fn >= 0) s.insert(in.fn);
  return {s.begin(), s.end()};
}

namespace {

using Key = std::tuple<int, int, int, int, std::uint32_t, int, int, int, int, int, int>;

// Builds the optimized instruction list: each instruction is folded (constants, identities, the
// rewrites below), then shared with an identical earlier one (common subexpressions).
class Folder {
 public:
  explicit Folder(bool fold_zero) : fold_zero_(fold_zero) {}
  std::vector<Inst> code;

  // The instruction `in` (arguments already renamed into `code`) reduces to.
  int put(Inst in) {
    for (int round = 0; round < 8; ++round) {
      canonicalize(&in);
      const int same = simplify(&in);
      if (same >= 0) return same;
      if (same == kStays) break;
    }
    return intern(in);
  }

 private:
  static constexpr int kStays = -1, kRewritten = -2;
  bool fold_zero_;
  std::map<Key, int> seen_;

  int intern(const Inst& in) {
    std::uint32_t kbits;
    std::memcpy(&kbits, &in.k, sizeof kbits);
    const Key key = std::make_tuple(static_cast<int>(in.op), in.fn, in.tex, in.channel, kbits, in.arg[0],
                                    in.arg[1], in.arg[2], in.arg[3], in.arg[4], in.arg[5]);
    auto it = seen_.find(key);
    if (it != seen_.end()) return it->second;
    code.push_back(in);
    return seen_[key] = static_cast<int>(code.size()) - 1;
  }
  int konst(float v) {
    Inst c;
    c.op = LOp::Const;
    c.k = v;
    return intern(c);
  }
  bool is_k(int i) const { return code[i].op == LOp::Const; }
  bool is_k(int i, float v) const { return is_k(i) && code[i].k == v; }

  // Known >= 0 and not NaN (+inf allowed). A footprint sd is >= 0 by construction.
  bool nonneg(int i) const {
    const Inst& c = code[i];
    switch (c.op) {
      case LOp::Const:
        return c.k >= 0.0f;
      case LOp::InSd:
      case LOp::NonNeg:
        return true;
      case LOp::Sqrt:
        return nonneg(c.arg[0]);
      case LOp::Add:
      case LOp::Max:  // a < b ? b : a: NaN only from a NaN argument
        return nonneg(c.arg[0]) && nonneg(c.arg[1]);
      case LOp::Mul:  // x * x; x * k (k finite and > 0: 0 * inf is NaN)
        return (c.arg[0] == c.arg[1] && nonneg(c.arg[0])) ||
               (nonneg(c.arg[0]) && is_k(c.arg[1]) && code[c.arg[1]].k > 0.0f);
      default:
        return false;
    }
  }

  // Add and Mul are commutative in IEEE arithmetic (bit for bit): constant second, else the
  // earlier argument first, so a + b and b + a share one instruction.
  void canonicalize(Inst* in) const {
    if (in->op != LOp::Add && in->op != LOp::Mul) return;
    const int a = in->arg[0], b = in->arg[1];
    if ((is_k(a) && !is_k(b)) || (is_k(a) == is_k(b) && a > b)) std::swap(in->arg[0], in->arg[1]);
  }

  // Folds arithmetic on constants (in float, as the emitted code computes it) and removes
  // identities. Returns the instruction `in` reduces to, kRewritten when `in` became another
  // instruction worth folding again, or kStays.
  //   x + 0, x - 0, x * 1, x / 1 -> x;  0 - x, x * -1 -> -x;  -(-x) -> x
  //   x * 0, 0 * x -> 0 (for finite x, identical; an infinite or NaN x no longer makes it NaN:
  //     these are the zero covariance and zero derivative terms of the lowering)
  //   (x * k1) * k2 -> x * (k1 k2) (one rounding fewer);  x / k -> x * (1 / k) for k a power of 2
  //   sqrt(x * x) -> x for x >= 0; sqrt(y * k) -> sqrt(y) * sqrt(k) (so sqrt(4 sd^2) is 2 sd);
  //   NonNeg(x) -> x for x known >= 0 and not NaN
  int simplify(Inst* in) {
    auto kv = [&](int j) { return code[in->arg[j]].k; };
    const int n = lop_arity(*in);
    bool all_const =
        n > 0 && in->op != LOp::Call && in->op != LOp::CallStat && in->op != LOp::Mean && in->op != LOp::Var;
    for (int j = 0; j < n && all_const; ++j) all_const = is_k(in->arg[j]);
    if (all_const) {
      float v = 0;
      switch (in->op) {
        case LOp::Add:
          v = kv(0) + kv(1);
          break;
        case LOp::Sub:
          v = kv(0) - kv(1);
          break;
        case LOp::Mul:
          v = kv(0) * kv(1);
          break;
        case LOp::Div:
          v = kv(0) / kv(1);
          break;
        case LOp::Neg:
          v = -kv(0);
          break;
        case LOp::Min:
          v = kv(0) < kv(1) ? kv(0) : kv(1);
          break;
        case LOp::Max:
          v = kv(0) < kv(1) ? kv(1) : kv(0);
          break;
        case LOp::Less:
          v = kv(0) < kv(1) ? 1.0f : 0.0f;
          break;
        case LOp::Sqrt:
          v = std::sqrt(kv(0));
          break;
        case LOp::NonNeg:
          v = kv(0) > 0.0f ? kv(0) : 0.0f;
          break;
        default:
          return kStays;
      }
      if (std::isfinite(v)) return konst(v);
      return kStays;
    }
    const int a = in->arg[0], b = in->arg[1];
    auto become = [&](LOp op, int x, int y = -1) {
      Inst r;
      r.op = op;
      r.arg[0] = x;
      r.arg[1] = y;
      *in = r;
      return kRewritten;
    };
    switch (in->op) {
      case LOp::Add:  // constants are second (canonicalize)
        if (is_k(b, 0.0f)) return a;
        break;
      case LOp::Sub:
        if (is_k(b, 0.0f)) return a;
        if (is_k(a, 0.0f)) return become(LOp::Neg, b);
        // k - (k - x) -> x: a pulse's complement taken twice (checkerboard's 1 - ss of ss = 1 - square).
        if (is_k(a) && code[b].op == LOp::Sub && is_k(code[b].arg[0]) && code[code[b].arg[0]].k == code[a].k)
          return code[b].arg[1];
        break;
      case LOp::Mul:
        if (is_k(b, 1.0f)) return a;
        if (is_k(b, 0.0f) && fold_zero_) return konst(0.0f);
        if (is_k(b, -1.0f)) return become(LOp::Neg, a);
        if (is_k(b) && code[a].op == LOp::Mul && is_k(code[a].arg[1])) {
          const int x = code[a].arg[0];
          const float k = code[code[a].arg[1]].k * code[b].k;
          if (std::isfinite(k) && k != 0.0f) return become(LOp::Mul, x, konst(k));
        }
        break;
      case LOp::Div:
        if (is_k(b, 1.0f)) return a;
        if (is_k(b)) {
          int e = 0;
          const float m = std::frexp(code[b].k, &e);
          const float inv = 1.0f / code[b].k;
          if ((m == 0.5f || m == -0.5f) && std::isnormal(inv)) {
            const int k = konst(inv);
            return become(LOp::Mul, a, k);
          }
        }
        break;
      case LOp::Neg:
        if (code[a].op == LOp::Neg) return code[a].arg[0];
        break;
      case LOp::Sqrt: {
        const Inst x = code[a];  // copies: put() and konst() may grow `code`
        if (x.op == LOp::Mul && x.arg[0] == x.arg[1] && nonneg(x.arg[0])) return x.arg[0];
        // sqrt(y k) = sqrt(y) sqrt(k) for k > 0 and any y (NaN for y < 0 either way), so that
        // sqrt(9 var) and sqrt(var) share one sqrt, and sqrt(4 sd^2) is 2 sd.
        if (x.op == LOp::Mul && is_k(x.arg[1]) && code[x.arg[1]].k > 0.0f) {
          const float rk = std::sqrt(code[x.arg[1]].k);
          Inst root;
          root.op = LOp::Sqrt;
          root.arg[0] = x.arg[0];
          const int r = put(root);
          const int k = konst(rk);
          return become(LOp::Mul, r, k);
        }
        break;
      }
      case LOp::NonNeg:
        if (nonneg(a)) return a;
        break;
      default:
        break;
    }
    return kStays;
  }
};

}  // namespace

Program optimize(const Program& p, const OptimizeOptions& opt) {
  // 1. Folding and common subexpressions, in program order.
  const int n = static_cast<int>(p.insts.size());
  std::vector<int> rename(n);
  Folder f(opt.fold_zero_products);
  for (int i = 0; i < n; ++i) {
    Inst in = p.insts[i];
    for (int j = 0; j < lop_arity(in); ++j) in.arg[j] = rename[in.arg[j]];
    rename[i] = f.put(in);
  }
  const std::vector<Inst>& unique = f.code;
  // 2. Dead code: keep what the outputs reach.
  std::vector<char> live(unique.size(), 0);
  for (int o : p.outputs) live[rename[o]] = 1;
  for (int i = static_cast<int>(unique.size()) - 1; i >= 0; --i)
    if (live[i])
      for (int j = 0; j < lop_arity(unique[i]); ++j) live[unique[i].arg[j]] = 1;
  Program out = p.interface_only();
  std::vector<int> pos(unique.size(), -1);
  for (std::size_t i = 0; i < unique.size(); ++i) {
    if (!live[i]) continue;
    Inst in = unique[i];
    for (int j = 0; j < lop_arity(in); ++j) in.arg[j] = pos[in.arg[j]];
    pos[i] = static_cast<int>(out.insts.size());
    out.insts.push_back(in);
  }
  for (int o : p.outputs) out.outputs.push_back(pos[rename[o]]);
  return out;
}

}  // namespace bl::compiler
