// The plain (unsmoothed) meaning of the graph's arithmetic ops, one definition for every
// interpreter: the double evaluator of compiler/plain_eval, the float NativeProgram of glsl/ and
// ir::Graph's constant folding. Const, Input, Call and Texture read state the interpreters hold
// and stay with them.
#pragma once

#include "ir/graph.hpp"

namespace bl::ir {

// Sets *y to op(a, b, c) and returns true for the arithmetic ops; false for the others. k is Mod's
// modulus and floor_fn the floor it uses (the catalog's plain floor, as the C++ templates' mod);
// select(c, a, b) is c a + (1 - c) b, as the templates compute it.
template <class T, class Floor>
inline bool plain_arith(Op op, T a, T b, T c, T k, Floor floor_fn, T* y) {
  switch (op) {
    case Op::Add:
      *y = a + b;
      return true;
    case Op::Sub:
      *y = a - b;
      return true;
    case Op::Mul:
      *y = a * b;
      return true;
    case Op::Div:
      *y = a / b;
      return true;
    case Op::Neg:
      *y = -a;
      return true;
    case Op::Min:
      *y = b < a ? b : a;
      return true;
    case Op::Max:
      *y = a < b ? b : a;
      return true;
    case Op::Less:
      *y = a < b ? T(1) : T(0);
      return true;
    case Op::Select:
      *y = a * b + (T(1) - a) * c;
      return true;
    case Op::Mod:
      *y = a - k * floor_fn(a / k);
      return true;
    default:
      return false;
  }
}

}  // namespace bl::ir
