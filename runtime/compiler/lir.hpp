// The lowered program: straight-line scalar code in SSA form. Lowering (lower.hpp) turns the traced
// DAG plus a rule per node into this; three back ends read it: C++ and GLSL printers and the batch
// evaluator, so the emitted code and the tuner's evaluator compute the same operations in the same
// order. Every instruction yields one float, except CallStat, which yields a (mean, var) pair read
// by Mean/Var.
#pragma once

#include <string>
#include <vector>

#include "compiler/functions.hpp"

namespace bl::compiler {

enum class LOp {
  Const,    // k
  InMean,   // input slot a: per-pixel mean
  InSd,     // input slot a: per-pixel standard deviation
  InGradX,  // input slot a: d mean / d screen x
  InGradY,  // input slot a: d mean / d screen y
  Add,
  Sub,
  Mul,
  Div,
  Neg,
  Min,
  Max,
  Less,      // a < b ? 1 : 0
  Sqrt,      // sqrt(a)
  NonNeg,    // a > 0 ? a : 0 (variance from E[f^2] - E[f]^2 can round below 0)
  Call,      // fn(args...) -> float
  CallStat,  // fn(args...) -> (mean, var)
  Mean,      // .mean of CallStat / TexStat a
  Var,       // .var of CallStat / TexStat a
  TexPlain,  // channel `channel` of texture slot `tex` at (a, b), level 0 bilinear -> float
  TexStat,   // the same over a footprint of sds (c, d): (mean, var) from the two pyramids
};

struct Inst {
  LOp op = LOp::Const;
  int arg[6] = {-1, -1, -1, -1, -1, -1};
  int fn = -1;      // index into functions() for Call/CallStat
  float k = 0;      // Const value
  int tex = -1;     // TexPlain/TexStat: texture slot (Program::texture_names)
  int channel = 0;  // TexPlain/TexStat: channel
  bool operator==(const Inst& o) const;
};

int lop_arity(const Inst& in);  // number of used args

struct Program {
  std::vector<Inst> insts;
  std::vector<int> outputs;  // instruction per output
  std::vector<std::string> output_names;
  int input_count = 0;  // slots of the InMean/InSd/InGrad arrays
  std::vector<std::string> input_names;
  std::vector<std::string> texture_names;  // texture slots, in slot order
  std::vector<std::string> notes;          // rule substitutions made while lowering (for reports)

  bool uses_gradients() const;
  // A program with no instructions and this one's interface: inputs, output names, textures, notes
  // (what a pass that rebuilds the instructions starts from).
  Program interface_only() const;
  bool uses_textures() const { return !texture_names.empty(); }
  bool pair_valued(int i) const { return insts[i].op == LOp::CallStat || insts[i].op == LOp::TexStat; }
  std::vector<int> used_functions() const;  // sorted indices into functions()
};

// Folding, common subexpression elimination and dead-code elimination (only what outputs need
// survives, so variances no later rule consumes are never computed). Folding: constants (in float),
// identities, k - (k - x) -> x, x * 0 -> 0 (so a zero covariance or derivative term drops what feeds it; an
// infinite or NaN x no longer turns it into NaN), constant chains (x * k1) * k2 -> x * (k1 k2),
// x / 2^n -> x * 2^-n, sqrt(k y) -> sqrt(k) sqrt(y) and sqrt(x^2) -> x for x >= 0 (a scaled
// sd), NonNeg of a value known >= 0; a + b and b + a are one instruction. Values change by float rounding at
// most (reassociated constant products, sqrt(k y), k - (k - x)) for finite operands.
struct OptimizeOptions {
  // x * 0 -> 0. It differs from the naive program where x is infinite or NaN: there the naive
  // product is NaN, which a later NonNeg / Min / Max may turn into an arbitrary finite value (a
  // covariance term 0 * sd_a * sd_b with an infinite variance collapses the sum of variances to 0).
  bool fold_zero_products = true;
};
Program optimize(const Program& p, const OptimizeOptions& opt = {});

}  // namespace bl::compiler
