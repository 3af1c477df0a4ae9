// The shader language: the catalog's functions and the non-arithmetic operators, for float and
// double (plain evaluation through the generated bl::plain:: functions, so native runs use exactly
// the catalog's definitions) and for the tracing Var. GENERATED-LIKE but hand-kept: one line per
// atomic; tests/runtime/dsl_test.cpp checks the list against the generated registry.
#pragma once

#include <bandlimit/table.hpp>

#include "dsl/trace.hpp"

namespace bl::dsl {

#define BL_DSL_ATOMIC(name)      \
  inline float name(float x) {   \
    return bl::plain::name(x);   \
  }                              \
  inline double name(double x) { \
    return bl::plain::name(x);   \
  }                              \
  inline Var name(Var x) {       \
    return call(#name, x);       \
  }

BL_DSL_ATOMIC(sin)
BL_DSL_ATOMIC(cos)
BL_DSL_ATOMIC(tan)
BL_DSL_ATOMIC(exp)
BL_DSL_ATOMIC(log)
BL_DSL_ATOMIC(sqrt)
BL_DSL_ATOMIC(sinh)
BL_DSL_ATOMIC(cosh)
BL_DSL_ATOMIC(tanh)
BL_DSL_ATOMIC(abs)
BL_DSL_ATOMIC(sign)
BL_DSL_ATOMIC(step)
BL_DSL_ATOMIC(floor)
BL_DSL_ATOMIC(ceil)
BL_DSL_ATOMIC(fract)
BL_DSL_ATOMIC(trunc)
BL_DSL_ATOMIC(saturate)
BL_DSL_ATOMIC(smoothstep)
BL_DSL_ATOMIC(pow2)
BL_DSL_ATOMIC(pow3)
BL_DSL_ATOMIC(pow4)
BL_DSL_ATOMIC(pow5)
BL_DSL_ATOMIC(pow6)
BL_DSL_ATOMIC(pow7)
BL_DSL_ATOMIC(pow8)
BL_DSL_ATOMIC(inv)
BL_DSL_ATOMIC(inv2)
BL_DSL_ATOMIC(triangle)
BL_DSL_ATOMIC(square)
BL_DSL_ATOMIC(pulse30)
BL_DSL_ATOMIC(xexp)
BL_DSL_ATOMIC(laplace)
BL_DSL_ATOMIC(exp_decay)
BL_DSL_ATOMIC(exp_ramp)
BL_DSL_ATOMIC(atan)
#undef BL_DSL_ATOMIC

// The atomics above, by name (the test compares them with the registry).
inline constexpr const char* kDslAtomics[] = {
    "sin",      "cos",    "tan",     "exp",   "log",     "sqrt",      "sinh",     "cosh",     "tanh",
    "abs",      "sign",   "step",    "floor", "ceil",    "fract",     "trunc",    "saturate", "smoothstep",
    "pow2",     "pow3",   "pow4",    "pow5",  "pow6",    "pow7",      "pow8",     "inv",      "inv2",
    "triangle", "square", "pulse30", "xexp",  "laplace", "exp_decay", "exp_ramp", "atan"};

// Operators beyond + - * /. less(a, b) is 1 where a < b, else 0; select(c, a, b) = c a + (1 - c) b
// for a 0/1 condition c (branches become selects); mod(a, c) = a - c floor(a / c), c a constant.
inline float min(float a, float b) {
  return a < b ? a : b;
}
inline double min(double a, double b) {
  return a < b ? a : b;
}
inline Var min(Var a, Var b) {
  return make(ir::Op::Min, a, b);
}
inline float max(float a, float b) {
  return a < b ? b : a;
}
inline double max(double a, double b) {
  return a < b ? b : a;
}
inline Var max(Var a, Var b) {
  return make(ir::Op::Max, a, b);
}
inline float less(float a, float b) {
  return a < b ? 1.0f : 0.0f;
}
inline double less(double a, double b) {
  return a < b ? 1.0 : 0.0;
}
inline Var less(Var a, Var b) {
  return make(ir::Op::Less, a, b);
}
template <class S>
S greater(S a, S b) {
  return less(b, a);
}
inline float select(float c, float a, float b) {
  return c * a + (1 - c) * b;
}
inline double select(double c, double a, double b) {
  return c * a + (1 - c) * b;
}
inline Var select(Var c, Var a, Var b) {
  return make(ir::Op::Select, c, a, b);
}
inline float mod(float a, double c) {
  return a - static_cast<float>(c) * bl::plain::floor(a / static_cast<float>(c));
}
inline double mod(double a, double c) {
  return a - c * bl::plain::floor(a / c);
}
Var mod(Var a, double c);

// Conveniences written in terms of the above (so they trace into primitive nodes).
template <class S>
S mix(S a, S b, S t) {
  return a + (b - a) * t;
}
// clamp to constant bounds through saturate (one atomic, smoothable).
template <class S>
S clamp(S x, double lo, double hi) {
  return S(lo) + S(hi - lo) * saturate((x - S(lo)) / S(hi - lo));
}
// GLSL's smoothstep(e0, e1, x) with constant edges.
template <class S>
S smoothstep(double e0, double e1, S x) {
  return smoothstep((x - S(e0)) / S(e1 - e0));
}
template <class S>
S step_edge(double edge, S x) {
  return step(x - S(edge));
}  // GLSL step(edge, x) up to the value at the edge

// The same with traced (variable) edges and divisors, as the GLSL front end maps them (overloads,
// not templates, so calls with constant edges keep the forms above).
// GLSL smoothstep(e0, e1, x) = smoothstep((x - e0) / (e1 - e0)).
inline Var smoothstep(Var e0, Var e1, Var x) {
  return smoothstep((x - e0) / (e1 - e0));
}
inline float smoothstep(float e0, float e1, float x) {
  return smoothstep((x - e0) / (e1 - e0));
}
// GLSL clamp(x, lo, hi) with varying bounds: min(max(x, lo), hi).
inline Var clamp(Var x, Var lo, Var hi) {
  return min(max(x, lo), hi);
}
inline float clamp(float x, float lo, float hi) {
  return min(max(x, lo), hi);
}
// GLSL mod(a, b) with a varying divisor: a - b floor(a / b).
inline Var mod(Var a, Var b) {
  return a - b * floor(a / b);
}
inline float mod(float a, float b) {
  return a - b * bl::plain::floor(a / b);
}

}  // namespace bl::dsl
