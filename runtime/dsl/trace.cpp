#include "dsl/trace.hpp"

#include <stdexcept>

namespace bl::dsl {
namespace {
thread_local ir::Graph* current = nullptr;
}

Tracer::Tracer(ir::Graph& g) : previous_(current) {
  current = &g;
}
Tracer::~Tracer() {
  current = previous_;
}

ir::Graph& Tracer::graph() {
  if (!current) throw std::logic_error("bl::dsl::Var used outside a bl::dsl::Tracer scope");
  return *current;
}

Var::Var(double c) : id_(Tracer::graph().constant(c)) {}

Var Var::input(const std::string& name, bool varying) {
  return node(Tracer::graph().input(name, varying));
}

Var make(ir::Op op, Var a) {
  ir::Node n;
  n.op = op;
  n.a = a.id();
  return Var::node(Tracer::graph().add(n));
}

Var make(ir::Op op, Var a, Var b) {
  ir::Node n;
  n.op = op;
  n.a = a.id();
  n.b = b.id();
  return Var::node(Tracer::graph().add(n));
}

Var make(ir::Op op, Var a, Var b, Var c) {
  ir::Node n;
  n.op = op;
  n.a = a.id();
  n.b = b.id();
  n.c = c.id();
  return Var::node(Tracer::graph().add(n));
}

Var call(const char* atomic, Var a) {
  return Var::node(Tracer::graph().call(atomic, a.id()));
}

}  // namespace bl::dsl
