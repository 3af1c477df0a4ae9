// The shader as traced: a DAG of scalar operations (the "algorithm" in Halide's terms). Nodes are
// appended in evaluation order, so index order is a topological order; identical nodes are shared
// (hash-consing) and operations on constants fold, so a traced shader is already minimal.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace bl::ir {

enum class Op : std::uint8_t {
  Const,    // value
  Input,    // value = input slot; a per-pixel random variable (mean, sd) or a uniform (sd 0)
  Add,      // a + b
  Sub,      // a - b
  Mul,      // a * b
  Div,      // a / b
  Neg,      // -a
  Min,      // min(a, b)
  Max,      // max(a, b)
  Less,     // 1 if a < b else 0 (= step(b - a))
  Select,   // c * a + (1 - c) * b, c a 0/1 condition
  Mod,      // a - value * floor(a / value), value a nonzero constant
  Call,     // atomic(a), atomic an index into bl::registry::kAtomics
  Texture,  // channel `atomic` of texture slot `value` at coordinates (a, b), wrapped (GL_REPEAT)
};

const char* op_name(Op op);
int op_arity(Op op);  // number of node arguments (Const/Input 0, Call/Neg/Mod 1, Select 3, else 2)

struct Node {
  Op op = Op::Const;
  int atomic = -1;  // Call: index into bl::registry::kAtomics; Texture: the channel
  int a = -1, b = -1, c = -1;
  double value = 0;  // Const: the constant; Input: the slot; Mod: the modulus; Texture: the slot
  bool operator==(const Node& o) const;
};

struct InputDecl {
  std::string name;
  bool varying = true;  // varying: mean and sd per pixel (surface coordinates); else a uniform
};

class Graph {
 public:
  // Adds a node (or returns the existing identical one, or folds constants). Throws
  // std::invalid_argument on a malformed node (bad argument index, Mod by 0, unknown atomic).
  int add(Node n);
  int constant(double v);
  int input(const std::string& name, bool varying);  // one node per name
  int call(const std::string& atomic, int a);        // throws naming an unknown atomic
  // Channel `channel` of the texture bound to slot `name` (one slot per name, in order of first
  // use) at coordinates (u, v).
  int texture(const std::string& name, int channel, int u, int v);
  int texture_slot(const std::string& name);  // the slot of `name`, declared now if new

  void add_output(const std::string& name, int node);

  const std::vector<Node>& nodes() const { return nodes_; }
  const Node& node(int i) const { return nodes_.at(i); }
  int size() const { return static_cast<int>(nodes_.size()); }
  const std::vector<InputDecl>& inputs() const { return inputs_; }
  const std::vector<std::string>& textures() const { return textures_; }  // slot names
  const std::vector<int>& outputs() const { return outputs_; }
  const std::vector<std::string>& output_names() const { return output_names_; }

  // Depth-first (post-order) list of the nodes reachable from the outputs: the order the tuner's
  // crossover and "adjacent node" mutations use.
  std::vector<int> depth_first_order() const;
  // Stable 64-bit hash of the structure (keys caches of ground truth and compiled variants).
  std::uint64_t hash() const;
  std::string to_string() const;  // one line per node, for debugging and error messages

 private:
  struct NodeHash {
    std::size_t operator()(const Node& n) const;
  };
  bool fold(const Node& n, double* out) const;

  std::vector<Node> nodes_;
  std::unordered_map<Node, int, NodeHash> index_;
  std::vector<InputDecl> inputs_;
  std::vector<std::string> textures_;
  std::vector<int> outputs_;
  std::vector<std::string> output_names_;
};

}  // namespace bl::ir
