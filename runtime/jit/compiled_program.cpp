#include "jit/compiled_program.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "compiler/emit.hpp"

namespace bl::jit {

namespace {

// The shader call with this pixel's gathered inputs (im, is, igx, igy) into o.
std::string call(const compiler::Program& p, const std::string& name) {
  return "bl_shaders::" + name + "(im, is, igx, igy, o" +
         (p.uses_textures() ? ", reinterpret_cast<const bl::texture::Texture* const*>(tex)" : "") + ");";
}

// bl_run: gathers each pixel's inputs (p's slots), runs `body` (which fills o), scatters o.
std::string batch_loop(const compiler::Program& p, bool gradients, const std::string& body) {
  const int ni = std::max(1, p.input_count), no = static_cast<int>(p.outputs.size());
  std::ostringstream os;
  os << "// Batch entry point: struct-of-arrays inputs (per slot) -> outputs, one pixel at a time.\n"
     << "extern \"C\" void bl_run(int n, const float* const* m, const float* const* s, const float* const* "
        "gx,\n"
     << "                       const float* const* gy, float* const* out, const void* const* tex) {\n"
     << "  (void)tex;\n"
     << "  for (int i = 0; i < n; ++i) {\n"
     << "    float im[" << ni << "] = {}, is[" << ni << "] = {}, igx[" << ni << "] = {}, igy[" << ni
     << "] = {};\n"
     << "    float o[" << no << "];\n"
     << "    for (int k = 0; k < " << p.input_count << "; ++k) {\n"
     << "      im[k] = m[k][i];\n      is[k] = s[k][i];\n"
     << (gradients ? "      igx[k] = gx[k][i];\n      igy[k] = gy[k][i];\n" : "") << "    }\n"
     << body << "    for (int k = 0; k < " << no << "; ++k) out[k][i] = o[k];\n"
     << "  }\n}\n";
  return os.str();
}

}  // namespace

std::string batch_source(const compiler::Program& p) {
  return compiler::emit_cpp(p, "shade", "compiled by bl::jit", compiler::CppForm::Source) + "\n" +
         batch_loop(p, p.uses_gradients(), "    " + call(p, "shade") + "\n");
}

std::string lod_batch_source(const compiler::Program& near, const compiler::Program& far, float limit) {
  return compiler::emit_cpp_lod(near, far, limit, "shade", "compiled by bl::jit", compiler::CppForm::Source) +
         "\n" +
         batch_loop(near, near.uses_gradients() || far.uses_gradients(), "    " + call(near, "shade") + "\n");
}

CompiledProgram::CompiledProgram(const compiler::Program& p, const Options& opt)
    : inputs_(p.input_count),
      outputs_(static_cast<int>(p.outputs.size())),
      textures_(static_cast<int>(p.texture_names.size())),
      gradients_(p.uses_gradients()),
      lib_(compile(batch_source(p), opt)) {
  entry_ = reinterpret_cast<Entry>(lib_->symbol("bl_run"));
}

CompiledProgram::CompiledProgram(const compiler::Program& near, const compiler::Program& far, float limit,
                                 const Options& opt)
    : inputs_(near.input_count),
      outputs_(static_cast<int>(near.outputs.size())),
      textures_(static_cast<int>(near.texture_names.size())),
      gradients_(near.uses_gradients() || far.uses_gradients()),
      lib_(compile(lod_batch_source(near, far, limit), opt)) {
  entry_ = reinterpret_cast<Entry>(lib_->symbol("bl_run"));
}

void CompiledProgram::run(const compiler::Batch& in, const std::vector<float*>& out) const {
  if (static_cast<int>(in.mean.size()) != inputs_ || static_cast<int>(in.sd.size()) != inputs_)
    throw std::invalid_argument("CompiledProgram: batch has " + std::to_string(in.mean.size()) +
                                " inputs, program " + std::to_string(inputs_));
  if (static_cast<int>(out.size()) != outputs_)
    throw std::invalid_argument("CompiledProgram: " + std::to_string(out.size()) + " output arrays for " +
                                std::to_string(outputs_) + " outputs");
  if (gradients_ && (in.grad_x.size() != in.mean.size() || in.grad_y.size() != in.mean.size()))
    throw std::invalid_argument("CompiledProgram: the program uses gradients but the batch has none");
  if (static_cast<int>(in.textures.size()) != textures_)
    throw std::invalid_argument("CompiledProgram: batch binds " + std::to_string(in.textures.size()) +
                                " textures, the program reads " + std::to_string(textures_));
  std::vector<const void*> tex(in.textures.begin(), in.textures.end());
  for (const void* t : tex)
    if (!t) throw std::invalid_argument("CompiledProgram: a texture is not bound");
  entry_(in.count, in.mean.data(), in.sd.data(), gradients_ ? in.grad_x.data() : nullptr,
         gradients_ ? in.grad_y.data() : nullptr, out.data(), tex.data());
}

}  // namespace bl::jit
