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

std::vector<int> Program::used_functions() const {
  std::set<int> s;
  for (const Inst& in : insts)
    if (in.fn >= 0) s.insert(in.fn);
  return {s.begin(), s.end()};
}

namespace {

// Folds arithmetic on constants (in float, as the emitted code would compute it) and removes
// identities (x + 0, x - 0, x * 1, x / 1). Returns the instruction `in` reduces to, or -1 when it
// stays (possibly rewritten into a constant).
int simplify(const std::vector<Inst>& code, Inst* in) {
  auto is_k = [&](int j) { return code[in->arg[j]].op == LOp::Const; };
  auto kv = [&](int j) { return code[in->arg[j]].k; };
  const int n = lop_arity(*in);
  bool all_const =
      n > 0 && in->op != LOp::Call && in->op != LOp::CallStat && in->op != LOp::Mean && in->op != LOp::Var;
  for (int j = 0; j < n && all_const; ++j) all_const = is_k(j);
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
        return -1;
    }
    if (std::isfinite(v)) {
      *in = Inst{};
      in->op = LOp::Const;
      in->k = v;
    }
    return -1;
  }
  switch (in->op) {
    case LOp::Add:
      if (is_k(1) && kv(1) == 0.0f) return in->arg[0];
      if (is_k(0) && kv(0) == 0.0f) return in->arg[1];
      break;
    case LOp::Sub:
      if (is_k(1) && kv(1) == 0.0f) return in->arg[0];
      break;
    case LOp::Mul:
      if (is_k(1) && kv(1) == 1.0f) return in->arg[0];
      if (is_k(0) && kv(0) == 1.0f) return in->arg[1];
      break;
    case LOp::Div:
      if (is_k(1) && kv(1) == 1.0f) return in->arg[0];
      break;
    default:
      break;
  }
  return -1;
}

}  // namespace

Program optimize(const Program& p) {
  // 1. Common subexpressions: identical instructions on identical (renamed) arguments.
  const int n = static_cast<int>(p.insts.size());
  std::vector<int> rename(n);
  std::vector<Inst> unique;
  std::map<std::tuple<int, int, int, int, std::uint32_t, int, int, int, int, int, int>, int> seen;
  for (int i = 0; i < n; ++i) {
    Inst in = p.insts[i];
    for (int j = 0; j < lop_arity(in); ++j) in.arg[j] = rename[in.arg[j]];
    const int same = simplify(unique, &in);
    if (same >= 0) {
      rename[i] = same;
      continue;
    }
    std::uint32_t kbits;
    std::memcpy(&kbits, &in.k, sizeof kbits);
    const auto key = std::make_tuple(static_cast<int>(in.op), in.fn, in.tex, in.channel, kbits, in.arg[0],
                                     in.arg[1], in.arg[2], in.arg[3], in.arg[4], in.arg[5]);
    auto it = seen.find(key);
    if (it != seen.end()) {
      rename[i] = it->second;
      continue;
    }
    unique.push_back(in);
    rename[i] = seen[key] = static_cast<int>(unique.size()) - 1;
  }
  // 2. Dead code: keep what the outputs reach.
  std::vector<char> live(unique.size(), 0);
  for (int o : p.outputs) live[rename[o]] = 1;
  for (int i = static_cast<int>(unique.size()) - 1; i >= 0; --i)
    if (live[i])
      for (int j = 0; j < lop_arity(unique[i]); ++j) live[unique[i].arg[j]] = 1;
  Program out;
  out.input_count = p.input_count;
  out.input_names = p.input_names;
  out.texture_names = p.texture_names;
  out.output_names = p.output_names;
  out.notes = p.notes;
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
