// See supersample.hpp.
#include "compiler/supersample.hpp"

#include <cmath>
#include <stdexcept>

namespace bl::compiler {

namespace {

// Phi^-1(p) for p in (0, 1): bisection on Phi (erfc), to double rounding; offsets are made once.
double normal_quantile(double p) {
  double lo = -40, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double radical_inverse_2(unsigned i) {
  double r = 0, f = 0.5;
  for (; i; i >>= 1, f *= 0.5)
    if (i & 1) r += f;
  return r;
}

}  // namespace

std::vector<std::array<float, 2>> supersample_offsets(int n, double sigma_px) {
  if (n < 1) throw std::invalid_argument("supersample: " + std::to_string(n) + " samples (at least 1)");
  if (!(sigma_px > 0) || !std::isfinite(sigma_px))
    throw std::invalid_argument("supersample: pixel sigma " + std::to_string(sigma_px) +
                                " is not finite and > 0");
  std::vector<std::array<float, 2>> out;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n, y = std::fmod(radical_inverse_2(static_cast<unsigned>(i)) + 0.5 / n, 1.0);
    out.push_back({static_cast<float>(sigma_px * normal_quantile(x)),
                   static_cast<float>(sigma_px * normal_quantile(y))});
  }
  return out;
}

Program supersample(const Program& plain, const std::vector<std::array<float, 2>>& offsets) {
  if (offsets.empty()) throw std::invalid_argument("supersample: no offsets");
  for (const Inst& in : plain.insts)
    if (in.op == LOp::InSd || in.op == LOp::InGradX || in.op == LOp::InGradY || in.op == LOp::CallStat ||
        in.op == LOp::TexStat)
      throw std::invalid_argument("supersample: the program is not plain (it reads sds, gradients or stats)");
  Program out = plain.interface_only();
  out.notes.push_back("supersampled: the plain program at " + std::to_string(offsets.size()) +
                      " offsets of the pixel, outputs averaged");
  auto emit = [&](const Inst& in) {
    out.insts.push_back(in);
    return static_cast<int>(out.insts.size()) - 1;
  };
  auto op = [&](LOp o, int a, int b = -1) {
    Inst in;
    in.op = o;
    in.arg[0] = a;
    in.arg[1] = b;
    return emit(in);
  };
  auto constant = [&](float k) {
    Inst in;
    in.op = LOp::Const;
    in.k = k;
    return emit(in);
  };
  std::vector<int> sum(plain.outputs.size(), -1);
  for (const auto& [ox, oy] : offsets) {
    std::vector<int> map(plain.insts.size(), -1);
    for (std::size_t i = 0; i < plain.insts.size(); ++i) {
      Inst in = plain.insts[i];
      if (in.op == LOp::InMean) {  // m + gx ox + gy oy
        Inst gx = in, gy = in;
        gx.op = LOp::InGradX;
        gy.op = LOp::InGradY;
        const int m = emit(in);
        const int dx = op(LOp::Mul, emit(gx), constant(ox)), dy = op(LOp::Mul, emit(gy), constant(oy));
        map[i] = op(LOp::Add, op(LOp::Add, m, dx), dy);
        continue;
      }
      for (int a = 0; a < lop_arity(in); ++a) in.arg[a] = map[in.arg[a]];
      map[i] = emit(in);
    }
    for (std::size_t o = 0; o < sum.size(); ++o) {
      const int v = map[plain.outputs[o]];
      sum[o] = sum[o] < 0 ? v : op(LOp::Add, sum[o], v);
    }
  }
  const int scale = constant(1.0f / static_cast<float>(offsets.size()));
  for (int s : sum) out.outputs.push_back(op(LOp::Mul, s, scale));
  return optimize(out);
}

Program stratified_samples(const Program& plain, int n, double sigma_px) {
  return n == 1 ? plain : supersample(plain, supersample_offsets(n, sigma_px));
}

Program one_sample(const Program& plain, int n, double sigma_px) {
  return n == 1 ? plain : supersample(plain, {supersample_offsets(n, sigma_px).front()});
}

}  // namespace bl::compiler
