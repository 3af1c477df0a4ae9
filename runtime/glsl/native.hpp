// Float evaluation of a traced pattern graph with exactly the plain semantics of the C++ templates
// instantiated with float (the catalog's plain functions, select as c a + (1 - c) b, mod through
// plain floor). Used for ground truth, MSAA and plain renders of GLSL shaders: the graph is resolved
// once into a flat instruction array of the nodes the outputs need; run() allocates nothing.
#pragma once

#include <vector>

#include "ir/graph.hpp"
#include "texture/texture.hpp"

namespace bl::glsl {

class NativeProgram {
 public:
  // `graph`'s inputs are bound by name: "u", "v", "time" (others read 0). Texture slots by name at
  // run time from the bindings.
  explicit NativeProgram(const ir::Graph& graph);
  // Writes the outputs (in graph order) to out[0..output_count).
  void run(float u, float v, float time, const texture::Bindings* textures, float* out) const;
  int output_count() const { return static_cast<int>(outputs_.size()); }
  int size() const { return static_cast<int>(code_.size()); }

 private:
  struct Inst {
    ir::Op op;
    int a, b, c;  // register indices (0 where absent)
    float k;      // Const value, Mod modulus
    float (*fn)(float);
    int input = -1;   // Input: 0 u, 1 v, 2 time, -1 other (reads 0)
    int channel = 0;  // Texture
    int slot = -1;    // Texture: index into slot_names_
  };
  std::vector<Inst> code_;
  std::vector<int> outputs_;  // registers
  std::vector<std::string> slot_names_;
};

}  // namespace bl::glsl
