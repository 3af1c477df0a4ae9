#include "dsl/math.hpp"

namespace bl::dsl {

Var mod(Var a, double c) {
  ir::Node n;
  n.op = ir::Op::Mod;
  n.a = a.id();
  n.value = c;
  return Var::node(Tracer::graph().add(n));
}

}  // namespace bl::dsl
