#include "compiler/evaluator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "texture/sample.hpp"

namespace bl::compiler {

Evaluator::Evaluator(const Program& p) : p_(p), base_(p.insts.size()) {
  int total = 0;
  for (std::size_t i = 0; i < p.insts.size(); ++i) {
    base_[i] = total;
    total += p.pair_valued(static_cast<int>(i)) ? 2 * kBlock : kBlock;
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
  if (in.textures.size() != p_.texture_names.size())
    throw std::invalid_argument("Evaluator: batch binds " + std::to_string(in.textures.size()) +
                                " textures, the program reads " + std::to_string(p_.texture_names.size()));
  for (std::size_t t = 0; t < in.textures.size(); ++t)
    if (!in.textures[t])
      throw std::invalid_argument("Evaluator: texture '" + p_.texture_names[t] + "' is not bound");
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
        case LOp::TexPlain: {
          const texture::Texture& tx = *in.textures[I.tex];
          const float *u = A(0), *v = A(1);
          for (int t = 0; t < m; ++t) r[t] = texture::sample_plain(tx, u[t], v[t], I.channel);
          break;
        }
        case LOp::TexStat: {
          const texture::Texture& tx = *in.textures[I.tex];
          const float *u = A(0), *v = A(1), *su = A(2), *sv = A(3);
          float* var = r + kBlock;
          for (int t = 0; t < m; ++t) {
            const bl::stat<float> s = texture::sample_stat(tx, u[t], v[t], su[t], sv[t], I.channel);
            r[t] = s.mean;
            var[t] = s.var;
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
