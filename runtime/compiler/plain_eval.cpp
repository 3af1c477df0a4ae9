#include "compiler/plain_eval.hpp"

#include <cmath>
#include <stdexcept>

#include "ir/atomics.hpp"
#include "ir/plain_ops.hpp"

namespace bl::compiler {

using ir::Op;

bool plain_node(const ir::Node& n, double a, double b, double c, double* y) {
  static const int floor_index = ir::atomic_index("floor");
  auto floor_fn = [](double x) { return ir::plain_atomic(floor_index, x); };
  if (ir::plain_arith(n.op, a, b, c, n.value, floor_fn, y)) return true;
  if (n.op == Op::Const) {
    *y = n.value;
    return true;
  }
  if (n.op == Op::Call) {
    *y = ir::plain_atomic(n.atomic, a);
    return true;
  }
  return false;
}

std::vector<double> plain_values(const ir::Graph& g, const std::vector<double>& inputs,
                                 const std::vector<const texture::Texture*>* textures) {
  std::vector<double> v(g.size());
  for (int i = 0; i < g.size(); ++i) {
    const ir::Node& n = g.node(i);
    const double a = n.a >= 0 ? v[n.a] : 0, b = n.b >= 0 ? v[n.b] : 0, c = n.c >= 0 ? v[n.c] : 0;
    if (plain_node(n, a, b, c, &v[i])) continue;
    switch (n.op) {
      case Op::Input:
        v[i] = inputs.at(static_cast<int>(n.value));
        break;
      case Op::Texture:
        if (!textures) {
          v[i] = std::nan("");
          break;
        }
        if (static_cast<std::size_t>(n.value) >= textures->size() || !(*textures)[int(n.value)])
          throw std::invalid_argument("plain_values: texture '" + g.textures().at(int(n.value)) +
                                      "' is not bound");
        v[i] = (*textures)[int(n.value)]->plain(static_cast<float>(a), static_cast<float>(b), n.atomic);
        break;
      default:  // arithmetic, constants and calls: plain_node above
        break;
    }
  }
  return v;
}

std::vector<double> plain_at_surface(const ir::Graph& g, double u, double v) {
  std::vector<double> in(g.inputs().size());
  for (std::size_t k = 0; k < in.size(); ++k) {
    const std::string& nm = g.inputs()[k].name;
    in[k] = nm == "u" ? u : nm == "v" ? v : (nm == "view_z" || nm == "light_z") ? 1 : 0;
  }
  return plain_values(g, in);
}

}  // namespace bl::compiler
