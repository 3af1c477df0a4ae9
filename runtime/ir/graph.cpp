#include "ir/graph.hpp"

#include <cmath>
#include <cstring>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "ir/atomics.hpp"
#include "ir/hash.hpp"
#include "ir/plain_ops.hpp"

namespace bl::ir {

const char* op_name(Op op) {
  switch (op) {
    case Op::Const:
      return "const";
    case Op::Input:
      return "input";
    case Op::Add:
      return "add";
    case Op::Sub:
      return "sub";
    case Op::Mul:
      return "mul";
    case Op::Div:
      return "div";
    case Op::Neg:
      return "neg";
    case Op::Min:
      return "min";
    case Op::Max:
      return "max";
    case Op::Less:
      return "less";
    case Op::Select:
      return "select";
    case Op::Mod:
      return "mod";
    case Op::Call:
      return "call";
    case Op::Texture:
      return "texture";
  }
  return "?";
}

int op_arity(Op op) {
  switch (op) {
    case Op::Const:
    case Op::Input:
      return 0;
    case Op::Neg:
    case Op::Mod:
    case Op::Call:
      return 1;
    case Op::Select:
      return 3;
    default:
      return 2;
  }
}

bool Node::operator==(const Node& o) const {
  // Constants compare by bit pattern so -0.0 and 0.0 (and NaNs) stay distinct nodes.
  return op == o.op && atomic == o.atomic && a == o.a && b == o.b && c == o.c &&
         std::memcmp(&value, &o.value, sizeof value) == 0;
}

std::size_t Graph::NodeHash::operator()(const Node& n) const {
  std::uint64_t bits;
  std::memcpy(&bits, &n.value, sizeof bits);
  std::size_t h = std::hash<std::uint64_t>()(bits);
  for (int v : {static_cast<int>(n.op), n.atomic, n.a, n.b, n.c}) h = h * 1000003u ^ std::hash<int>()(v);
  return h;
}

bool Graph::fold(const Node& n, double* out) const {
  auto is_const = [&](int i) { return i < 0 || nodes_[i].op == Op::Const; };
  if (n.op == Op::Const || n.op == Op::Input) return false;
  if (!is_const(n.a) || !is_const(n.b) || !is_const(n.c)) return false;
  auto v = [&](int i) { return i < 0 ? 0.0 : nodes_[i].value; };
  const double a = v(n.a), b = v(n.b), c = v(n.c);
  if (plain_arith(
          n.op, a, b, c, n.value, [](double x) { return std::floor(x); }, out))
    return true;
  if (n.op != Op::Call) return false;
  *out = plain_atomic(n.atomic, a);
  return true;
}

int Graph::add(Node n) {
  const int arity = op_arity(n.op);
  const int args[3] = {n.a, n.b, n.c};
  for (int k = 0; k < 3; ++k) {
    const bool used = k < arity;
    if (used && (args[k] < 0 || args[k] >= size()))
      throw std::invalid_argument(std::string("ir::Graph: ") + op_name(n.op) + " argument " +
                                  std::to_string(k) + " is not an existing node (" + std::to_string(args[k]) +
                                  ")");
    if (!used && args[k] != -1)
      throw std::invalid_argument(std::string("ir::Graph: ") + op_name(n.op) + " takes " +
                                  std::to_string(arity) + " arguments");
  }
  if (n.op == Op::Call && (n.atomic < 0 || n.atomic >= atomic_count()))
    throw std::invalid_argument("ir::Graph: call of unknown atomic index " + std::to_string(n.atomic));
  if (n.op == Op::Texture &&
      (n.atomic < 0 || n.atomic > 3 || n.value < 0 || n.value >= static_cast<double>(textures_.size())))
    throw std::invalid_argument("ir::Graph: texture lookup of channel " + std::to_string(n.atomic) +
                                " of slot " + std::to_string(n.value) +
                                " (slots: " + std::to_string(textures_.size()) + ", channels 0..3)");
  if (n.op != Op::Call && n.op != Op::Texture) n.atomic = -1;
  if (n.op == Op::Mod && !(std::isfinite(n.value) && n.value != 0))
    throw std::invalid_argument("ir::Graph: mod needs a finite nonzero constant modulus, got " +
                                std::to_string(n.value));
  double folded;
  if (fold(n, &folded)) return constant(folded);
  auto it = index_.find(n);
  if (it != index_.end()) return it->second;
  nodes_.push_back(n);
  index_.emplace(n, size() - 1);
  return size() - 1;
}

int Graph::constant(double v) {
  Node n;
  n.op = Op::Const;
  n.value = v;
  auto it = index_.find(n);
  if (it != index_.end()) return it->second;
  nodes_.push_back(n);
  index_.emplace(n, size() - 1);
  return size() - 1;
}

int Graph::input(const std::string& name, bool varying) {
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    if (inputs_[i].name != name) continue;
    if (inputs_[i].varying != varying)
      throw std::invalid_argument("ir::Graph: input '" + name + "' declared both varying and uniform");
    Node n;
    n.op = Op::Input;
    n.value = static_cast<double>(i);
    return index_.at(n);
  }
  inputs_.push_back({name, varying});
  Node n;
  n.op = Op::Input;
  n.value = static_cast<double>(inputs_.size() - 1);
  nodes_.push_back(n);
  index_.emplace(n, size() - 1);
  return size() - 1;
}

int Graph::call(const std::string& atomic, int a) {
  const int idx = atomic_index(atomic);
  if (idx < 0) throw std::invalid_argument("ir::Graph: unknown atomic function '" + atomic + "'");
  Node n;
  n.op = Op::Call;
  n.atomic = idx;
  n.a = a;
  return add(n);
}

int Graph::texture_slot(const std::string& name) {
  if (name.empty()) throw std::invalid_argument("ir::Graph: a texture slot needs a name");
  int slot = 0;
  while (slot < static_cast<int>(textures_.size()) && textures_[slot] != name) ++slot;
  if (slot == static_cast<int>(textures_.size())) textures_.push_back(name);
  return slot;
}

int Graph::texture(const std::string& name, int channel, int u, int v) {
  const int slot = texture_slot(name);
  Node n;
  n.op = Op::Texture;
  n.atomic = channel;
  n.value = slot;
  n.a = u;
  n.b = v;
  return add(n);
}

void Graph::add_output(const std::string& name, int node) {
  if (node < 0 || node >= size())
    throw std::invalid_argument("ir::Graph: output '" + name + "' names no node");
  for (const auto& o : output_names_)
    if (o == name) throw std::invalid_argument("ir::Graph: output '" + name + "' declared twice");
  outputs_.push_back(node);
  output_names_.push_back(name);
}

std::vector<int> Graph::depth_first_order() const {
  std::vector<int> order;
  std::vector<char> seen(nodes_.size(), 0);
  // Iterative post-order so deep shaders (unrolled loops) cannot overflow the stack.
  for (int root : outputs_) {
    std::vector<std::pair<int, int>> stack{{root, 0}};
    while (!stack.empty()) {
      auto& [id, k] = stack.back();
      if (seen[id] == 2) {
        stack.pop_back();
        continue;
      }
      seen[id] = 1;
      const Node& n = nodes_[id];
      const int args[3] = {n.a, n.b, n.c};
      if (k < op_arity(n.op)) {
        const int child = args[k++];
        if (!seen[child]) stack.push_back({child, 0});
        continue;
      }
      seen[id] = 2;
      order.push_back(id);
      stack.pop_back();
    }
  }
  return order;
}

std::uint64_t Graph::hash() const {
  return fnv1a(to_string());
}

std::string Graph::to_string() const {
  std::ostringstream os;
  os.precision(17);
  for (int i = 0; i < size(); ++i) {
    const Node& n = nodes_[i];
    os << "%" << i << " = " << op_name(n.op);
    if (n.op == Op::Const) os << " " << n.value;
    if (n.op == Op::Input)
      os << " " << inputs_[static_cast<int>(n.value)].name
         << (inputs_[static_cast<int>(n.value)].varying ? " varying" : " uniform");
    if (n.op == Op::Call) os << " " << atomic_name(n.atomic);
    if (n.op == Op::Texture) os << " " << textures_[static_cast<int>(n.value)] << "." << n.atomic;
    const int args[3] = {n.a, n.b, n.c};
    for (int k = 0; k < op_arity(n.op); ++k) os << " %" << args[k];
    if (n.op == Op::Mod) os << " " << n.value;
    os << "\n";
  }
  for (std::size_t k = 0; k < outputs_.size(); ++k)
    os << "out " << output_names_[k] << " = %" << outputs_[k] << "\n";
  return os.str();
}

}  // namespace bl::ir
