// A lowered Program as native code: its emit_cpp output plus a batch entry point, compiled with -O3
// by the JIT (jit.hpp) and called over the same struct-of-arrays inputs the evaluator takes. This is
// the code a renderer would run; the reports quote its time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "compiler/evaluator.hpp"
#include "compiler/lir.hpp"
#include "jit/jit.hpp"

namespace bl::jit {

// The translation unit compiled for `p`: the emitted shader (namespace bl_shaders, function shade)
// and `extern "C" void bl_run(...)`, which gathers each pixel's inputs from the batch arrays, calls
// the shader and scatters its outputs.
std::string batch_source(const compiler::Program& p);
// The same for a footprint-LOD pair (tuner/lod.hpp): compiler::emit_cpp_lod's shade (near below the
// footprint limit, far above; it throws std::invalid_argument for programs that do not pair).
std::string lod_batch_source(const compiler::Program& near, const compiler::Program& far, float limit);

class CompiledProgram {
 public:
  // Compiles (or loads from the cache) p's code. Throws jit::Error (compiler missing or failing).
  explicit CompiledProgram(const compiler::Program& p, const Options& opt = {});
  // A footprint-LOD pair in one loop (lod_batch_source); run() takes either program's inputs.
  CompiledProgram(const compiler::Program& near, const compiler::Program& far, float limit,
                  const Options& opt = {});
  // out[k][pixel] for each output k, like Evaluator::run (same checks). Thread-safe.
  void run(const compiler::Batch& in, const std::vector<float*>& out) const;
  const Library& library() const { return *lib_; }

 private:
  using Entry = void (*)(int, const float* const*, const float* const*, const float* const*,
                         const float* const*, float* const*, const void* const*);
  int inputs_ = 0, outputs_ = 0, textures_ = 0;
  bool gradients_ = false;
  std::shared_ptr<Library> lib_;
  Entry entry_ = nullptr;
};

}  // namespace bl::jit
