// The tracing scalar: a shader template instantiated with bl::dsl::Var records a DAG (ir::Graph)
// instead of computing, the way Dr.Jit traces. Instantiated with float or double the same template
// runs natively (math.hpp gives the plain catalog functions for those).
#pragma once

#include <string>

#include "ir/graph.hpp"

namespace bl::dsl {

// While a Tracer is alive on this thread, Var operations append to its graph.
class Tracer {
 public:
  explicit Tracer(ir::Graph& g);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;
  static ir::Graph& graph();  // throws std::logic_error outside a Tracer

 private:
  ir::Graph* previous_;
};

class Var {
 public:
  Var() : Var(0.0) {}                            // like float{}: the constant 0
  Var(double c);                                 // NOLINT: constants mix freely with traced values
  Var(float c) : Var(static_cast<double>(c)) {}  // NOLINT
  Var(int c) : Var(static_cast<double>(c)) {}    // NOLINT
  static Var node(int id) { return Var(id, Tag{}); }
  static Var input(const std::string& name, bool varying = true);
  int id() const { return id_; }

 private:
  struct Tag {};
  Var(int id, Tag) : id_(id) {}
  int id_;
};

Var make(ir::Op op, Var a);
Var make(ir::Op op, Var a, Var b);
Var make(ir::Op op, Var a, Var b, Var c);
Var call(const char* atomic, Var a);

inline Var operator+(Var a, Var b) {
  return make(ir::Op::Add, a, b);
}
inline Var operator-(Var a, Var b) {
  return make(ir::Op::Sub, a, b);
}
inline Var operator*(Var a, Var b) {
  return make(ir::Op::Mul, a, b);
}
inline Var operator/(Var a, Var b) {
  return make(ir::Op::Div, a, b);
}
inline Var operator-(Var a) {
  return make(ir::Op::Neg, a);
}
inline Var& operator+=(Var& a, Var b) {
  return a = a + b;
}
inline Var& operator-=(Var& a, Var b) {
  return a = a - b;
}
inline Var& operator*=(Var& a, Var b) {
  return a = a * b;
}
inline Var& operator/=(Var& a, Var b) {
  return a = a / b;
}

}  // namespace bl::dsl
