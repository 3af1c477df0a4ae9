#include "compiler/plain_eval.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ir/atomics.hpp"

namespace bl::compiler {

using ir::Op;

std::vector<double> plain_values(const ir::Graph& g, const std::vector<double>& inputs,
                                 const std::vector<const texture::Texture*>* textures) {
  std::vector<double> v(g.size());
  for (int i = 0; i < g.size(); ++i) {
    const ir::Node& n = g.node(i);
    const double a = n.a >= 0 ? v[n.a] : 0, b = n.b >= 0 ? v[n.b] : 0, c = n.c >= 0 ? v[n.c] : 0;
    switch (n.op) {
      case Op::Const:
        v[i] = n.value;
        break;
      case Op::Input:
        v[i] = inputs.at(static_cast<int>(n.value));
        break;
      case Op::Add:
        v[i] = a + b;
        break;
      case Op::Sub:
        v[i] = a - b;
        break;
      case Op::Mul:
        v[i] = a * b;
        break;
      case Op::Div:
        v[i] = a / b;
        break;
      case Op::Neg:
        v[i] = -a;
        break;
      case Op::Min:
        v[i] = std::min(a, b);
        break;
      case Op::Max:
        v[i] = std::max(a, b);
        break;
      case Op::Less:
        v[i] = a < b ? 1 : 0;
        break;
      case Op::Select:
        v[i] = a * b + (1 - a) * c;
        break;
      case Op::Mod:
        v[i] = a - n.value * std::floor(a / n.value);
        break;
      case Op::Call:
        v[i] = ir::plain_atomic(n.atomic, a);
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
    }
  }
  return v;
}

}  // namespace bl::compiler
