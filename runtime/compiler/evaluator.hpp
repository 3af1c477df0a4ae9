// The in-process evaluator the tuner uses: runs a lowered Program over pixel batches with the same
// operations, in the same order, as the emitted C++ and GLSL (float throughout).
#pragma once

#include <vector>

#include "compiler/lir.hpp"
#include "texture/texture.hpp"

namespace bl::compiler {

// Struct-of-arrays inputs for `count` pixels: per input slot, the mean, sd and screen gradient.
// Gradient arrays may be null when the program does not use gradients.
struct Batch {
  int count = 0;
  std::vector<const float*> mean, sd, grad_x, grad_y;  // size Program::input_count each
  std::vector<const texture::Texture*> textures;       // per Program::texture_names slot
};

class Evaluator {
 public:
  explicit Evaluator(const Program& p);
  // out[k][pixel] for each output k. Not thread-safe per instance: use one per thread.
  void run(const Batch& in, const std::vector<float*>& out);

 private:
  static constexpr int kBlock = 256;
  const Program& p_;
  std::vector<float> reg_;  // kBlock values per instruction (+ kBlock more for a CallStat's var)
  std::vector<int> base_;
};

}  // namespace bl::compiler
