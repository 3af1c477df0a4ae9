// The compiled variants compiler_test checks (emitted C++ against the evaluator, GLSL validation).
#pragma once

#include <string>
#include <vector>

#include "compiler/lower.hpp"
#include "shaders/shader.hpp"

namespace bl::test {

struct Fixture {
  std::string shader;
  shaders::Effects fx;
  std::string rule;
  std::string label() const {
    return shader + " parallax " + std::to_string(static_cast<int>(fx.parallax)) + " / " + rule;
  }
};

inline std::vector<Fixture> fixture_list() {
  std::vector<Fixture> out;
  const std::vector<std::string> rules = {"none", "dorn", "gaussian", "gaussian:rho=grad", "mc4", "box", "tent"};
  for (const auto& shader : shaders::base_shader_names())
    for (int p = 0; p < 3; ++p) {
      shaders::Effects fx;
      fx.parallax = static_cast<shaders::Parallax>(p);
      fx.lighting = p ? shaders::Lighting::Phong : shaders::Lighting::None;
      fx.animated = true;
      // Every rule on the parallax-free variant, two on the others (keeps the build short).
      for (const auto& r : rules)
        if (p == 0 || r == "gaussian" || r == "dorn") out.push_back({shader, fx, r});
    }
  return out;
}

inline compiler::Program compile_fixture(const Fixture& f) {
  const ir::Graph g = shaders::trace(shaders::find_shader(f.shader), f.fx);
  return compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(f.rule)));
}

}  // namespace bl::test
