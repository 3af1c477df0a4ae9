#include "compiler/evaluator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bl::compiler {

Evaluator::Evaluator(const Program& p) : p_(p), base_(p.insts.size()) {
  int total = 0;
  for (std::size_t i = 0; i < p.insts.size(); ++i) {
    base_[i] = total;
    total += p.insts[i].op == LOp::CallStat ? 2 * kBlock : kBlock;
  }
  reg_.assign(static_cast<std::size_t>(total), 0.0f);
}

void Evaluator::run(const Batch& in, const std::vector<float*>& out) {
  if (static_cast<int>(in.mean.size()) != p_.input_count || static_cast<int>(in.sd.size()) != p_.input_count)
    throw std::invalid_argument("Evaluator: batch has " + std::to_string(in.mean.size()) +
                                " inputs, program " + std::to_string(p_.input_count));
  if (out.size() != p_.outputs.size())
    throw std::invalid_argument("Evaluator: " + std::to_string(out.size()) + " output arrays for " +
                                std::to_string(p_.outputs.size()) + " outputs");
  if (p_.uses_gradients() && (in.grad_x.size() != in.mean.size() || in.grad_y.size() != in.mean.size()))
    throw std::invalid_argument("Evaluator: the program uses gradients but the batch has none");
  const auto& fns = functions();
  for (int start = 0; start < in.count; start += kBlock) {
    const int m = std::min(kBlock, in.count - start);
    for (std::size_t i = 0; i < p_.insts.size(); ++i) {
      const Inst& I = p_.insts[i];
      float* r = &reg_[base_[i]];
      auto A = [&](int j) { return &reg_[base_[I.arg[j]]]; };
      switch (I.op) {
        case LOp::Const:
          for (int t = 0; t < m; ++t) r[t] = I.k;
          break;
        case LOp::InMean:
          for (int t = 0; t < m; ++t) r[t] = in.mean[I.arg[0]][start + t];
          break;
        case LOp::InSd:
          for (int t = 0; t < m; ++t) r[t] = in.sd[I.arg[0]][start + t];
          break;
        case LOp::InGradX:
          for (int t = 0; t < m; ++t) r[t] = in.grad_x[I.arg[0]][start + t];
          break;
        case LOp::InGradY:
          for (int t = 0; t < m; ++t) r[t] = in.grad_y[I.arg[0]][start + t];
          break;
#define BL_BIN(OPCODE, EXPR)                   \
  case LOp::OPCODE: {                          \
    const float *a = A(0), *b = A(1);          \
    for (int t = 0; t < m; ++t) r[t] = (EXPR); \
    break;                                     \
  }
          BL_BIN(Add, a[t] + b[t])
          BL_BIN(Sub, a[t] - b[t])
          BL_BIN(Mul, a[t] * b[t])
          BL_BIN(Div, a[t] / b[t])
          BL_BIN(Min, a[t] < b[t] ? a[t] : b[t])
          BL_BIN(Max, a[t] < b[t] ? b[t] : a[t])
          BL_BIN(Less, a[t] < b[t] ? 1.0f : 0.0f)
#undef BL_BIN
        case LOp::Neg: {
          const float* a = A(0);
          for (int t = 0; t < m; ++t) r[t] = -a[t];
          break;
        }
        case LOp::Sqrt: {
          const float* a = A(0);
          for (int t = 0; t < m; ++t) r[t] = std::sqrt(a[t]);
          break;
        }
        case LOp::NonNeg: {
          const float* a = A(0);
          for (int t = 0; t < m; ++t) r[t] = a[t] > 0.0f ? a[t] : 0.0f;
          break;
        }
        case LOp::Mean: {
          const float* a = A(0);
          for (int t = 0; t < m; ++t) r[t] = a[t];
          break;
        }
        case LOp::Var: {
          const float* a = A(0) + kBlock;
          for (int t = 0; t < m; ++t) r[t] = a[t];
          break;
        }
        case LOp::Call: {
          const Function& f = fns[I.fn];
          if (f.arity == 1) {
            const float* a = A(0);
            for (int t = 0; t < m; ++t) r[t] = f.f1(a[t]);
          } else {
            const float *a = A(0), *b = A(1);
            for (int t = 0; t < m; ++t) r[t] = f.f2(a[t], b[t]);
          }
          break;
        }
        case LOp::CallStat: {
          const Function& f = fns[I.fn];
          float* v = r + kBlock;
          bl::stat<float> s{};
          for (int t = 0; t < m; ++t) {
            switch (f.arity) {
              case 2:
                s = f.s2(A(0)[t], A(1)[t]);
                break;
              case 3:
                s = f.s3(A(0)[t], A(1)[t], A(2)[t]);
                break;
              case 5:
                s = f.s5(A(0)[t], A(1)[t], A(2)[t], A(3)[t], A(4)[t]);
                break;
              case 6:
                s = f.s6(A(0)[t], A(1)[t], A(2)[t], A(3)[t], A(4)[t], A(5)[t]);
                break;
              default:
                throw std::logic_error("Evaluator: stat function of arity " + std::to_string(f.arity));
            }
            r[t] = s.mean;
            v[t] = s.var;
          }
          break;
        }
      }
    }
    for (std::size_t o = 0; o < p_.outputs.size(); ++o) {
      const float* r = &reg_[base_[p_.outputs[o]]];
      for (int t = 0; t < m; ++t) out[o][start + t] = r[t];
    }
  }
}

}  // namespace bl::compiler
