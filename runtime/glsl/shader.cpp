#include "glsl/shader.hpp"

#include <filesystem>

#include "glsl/native.hpp"
#include "shaders/effects.hpp"

namespace bl::glsl {

using dsl::Var;

dsl::Vec3<Var> replay(const ir::Graph& p, Var u, Var v, Var time) {
  ir::Graph& g = dsl::Tracer::graph();
  std::vector<int> id(p.size(), -1);
  for (int i = 0; i < p.size(); ++i) {
    const ir::Node& n = p.node(i);
    switch (n.op) {
      case ir::Op::Const:
        id[i] = g.constant(n.value);
        break;
      case ir::Op::Input: {
        const std::string& name = p.inputs()[static_cast<int>(n.value)].name;
        id[i] = (name == "u" ? u : name == "v" ? v : name == "time" ? time : Var(0.0)).id();
        break;
      }
      case ir::Op::Texture:
        id[i] = g.texture(p.textures()[static_cast<int>(n.value)], n.atomic, id[n.a], id[n.b]);
        break;
      default: {
        ir::Node m = n;
        if (m.a >= 0) m.a = id[m.a];
        if (m.b >= 0) m.b = id[m.b];
        if (m.c >= 0) m.c = id[m.c];
        id[i] = g.add(m);
      }
    }
  }
  const auto& out = p.outputs();
  return {Var::node(id[out.at(0)]), Var::node(id[out.at(1)]), Var::node(id[out.at(2)])};
}

shaders::ShaderDef make_shader(std::shared_ptr<const Pattern> pattern, const std::string& name) {
  auto native = std::make_shared<const NativeProgram>(pattern->graph);
  shaders::ShaderDef d;
  d.name = name;
  d.description = "GLSL pattern " + pattern->file;
  d.uses_time = pattern->uses_time;
  for (const auto& t : pattern->textures) d.textures.push_back({t, 3, texture::Encoding::Srgb});
  d.native = [native](const shaders::Inputs<float>& in, const shaders::Effects& fx) {
    const shaders::Surface<float> s = shaders::surface(in, fx);
    float rgb[3];
    native->run(s.uv.x, s.uv.y, in.time, in.textures, rgb);
    return shaders::light(dsl::Vec3<float>{rgb[0], rgb[1], rgb[2]}, s, in, fx);
  };
  d.traced = [pattern](const shaders::Inputs<Var>& in, const shaders::Effects& fx) {
    const shaders::Surface<Var> s = shaders::surface(in, fx);
    return shaders::light(replay(pattern->graph, s.uv.x, s.uv.y, in.time), s, in, fx);
  };
  return d;
}

std::shared_ptr<const shaders::ShaderDef> load_shader(const std::string& path) {
  auto p = std::make_shared<const Pattern>(trace_file(path));
  return std::make_shared<const shaders::ShaderDef>(
      make_shader(p, std::filesystem::path(path).stem().string()));
}

}  // namespace bl::glsl
