#include "glsl/native.hpp"

#include <stdexcept>

#include "ir/atomics.hpp"
#include "ir/plain_ops.hpp"

namespace bl::glsl {

NativeProgram::NativeProgram(const ir::Graph& g) : slot_names_(g.textures()) {
  // Registers in depth-first order of the outputs: only what they need, arguments first.
  std::vector<int> reg(g.size(), -1);
  for (int id : g.depth_first_order()) {
    const ir::Node& n = g.node(id);
    Inst in{n.op, -1, -1, -1, 0.0f, nullptr};
    // An absent argument reads register 0 (its value unused), so run() loads without a branch.
    in.a = n.a >= 0 ? reg[n.a] : 0;
    in.b = n.b >= 0 ? reg[n.b] : 0;
    in.c = n.c >= 0 ? reg[n.c] : 0;
    in.k = static_cast<float>(n.value);
    if (n.op == ir::Op::Input) {
      const std::string& name = g.inputs()[static_cast<int>(n.value)].name;
      in.input = name == "u" ? 0 : name == "v" ? 1 : name == "time" ? 2 : -1;
    }
    if (n.op == ir::Op::Call) in.fn = ir::plain_atomic_fn(n.atomic);
    if (n.op == ir::Op::Mod) in.fn = ir::plain_atomic_fn(ir::atomic_index("floor"));
    if (n.op == ir::Op::Texture) {
      in.channel = n.atomic;
      in.slot = static_cast<int>(n.value);
    }
    reg[id] = static_cast<int>(code_.size());
    code_.push_back(in);
  }
  for (int o : g.outputs()) outputs_.push_back(reg[o]);
}

void NativeProgram::run(float u, float v, float time, const texture::Bindings* textures, float* out) const {
  // One register file per thread, grown to the largest program seen: no allocation per call.
  thread_local std::vector<float> r;
  if (r.size() < code_.size()) r.resize(code_.size());
  const float in[3] = {u, v, time};
  float* x = r.data();
  const std::size_t n = code_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Inst& c = code_[i];
    float y = 0;
    const float a = x[c.a], b = x[c.b], cc = x[c.c];
    if (ir::plain_arith(c.op, a, b, cc, c.k, c.fn, &x[i])) continue;
    switch (c.op) {
      case ir::Op::Const:
        y = c.k;
        break;
      case ir::Op::Input:
        y = c.input >= 0 ? in[c.input] : 0.0f;
        break;
      case ir::Op::Call:
        y = c.fn(x[c.a]);
        break;
      case ir::Op::Texture: {
        const texture::Texture* t = textures ? texture::find(*textures, slot_names_[c.slot]) : nullptr;
        if (!t)
          throw std::invalid_argument("GLSL shader reads texture slot '" + slot_names_[c.slot] +
                                      "', which the scene does not bind");
        y = t->plain(x[c.a], x[c.b], c.channel);
        break;
      }
      default:  // arithmetic: plain_arith above
        break;
    }
    x[i] = y;
  }
  for (std::size_t k = 0; k < outputs_.size(); ++k) out[k] = x[outputs_[k]];
}

}  // namespace bl::glsl
