// The 7 base patterns written in GLSL (scenes/glsl/) trace to graphs whose plain and smoothed values
// equal the C++ templates' (runtime/shaders/patterns.hpp): every deterministic rule of
// rules::all_rules() as a uniform schedule (Monte Carlo rules draw their samples by node index, so
// two equal graphs numbered differently give different, equally valid estimates), through compiler::lower +
// Evaluator, on random pixel inputs (means and sds), with and without parallax and lighting.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compiler/evaluator.hpp"
#include "compiler/lower.hpp"
#include "glsl/shader.hpp"
#include "shaders/shader.hpp"
#include "tests/runtime/random_pixels.hpp"

namespace bl {
namespace {

std::vector<std::vector<float>> run(const compiler::Program& p, int n) {
  const testing::RandomPixels in(
      p, n, 7, 6.0f, 0.5f);  // same seed: both programs see the same pixels (their inputs are named alike)
  std::vector<std::vector<float>> out(p.outputs.size(), std::vector<float>(n));
  std::vector<float*> ptr;
  for (auto& o : out) ptr.push_back(o.data());
  compiler::Evaluator(p).run(in.batch(), ptr);
  return out;
}

TEST(GlslSuite, BasePatternsEqualTheCppTemplatesUnderEveryRule) {
  const int n = 512;
  for (const std::string& name : shaders::base_shader_names()) {
    const auto glsl_def = glsl::load_shader(std::string(BL_SCENES_DIR) + "/glsl/" + name + ".glsl");
    const shaders::ShaderDef& cpp_def = shaders::find_shader(name);
    EXPECT_EQ(glsl_def->uses_time, cpp_def.uses_time) << name;
    for (int fxi = 0; fxi < 3; ++fxi) {
      shaders::Effects fx;
      fx.animated = fxi > 0;
      if (fxi > 0) fx.lighting = shaders::Lighting::Phong;
      fx.parallax = fxi == 1   ? shaders::Parallax::Bumps
                    : fxi == 2 ? shaders::Parallax::Ripples
                               : shaders::Parallax::None;
      const ir::Graph gg = shaders::trace(*glsl_def, fx), gc = shaders::trace(cpp_def, fx);
      ASSERT_EQ(gg.inputs().size(), gc.inputs().size()) << name;
      for (const rules::Rule& rule : rules::all_rules()) {
        if (rule.kind == rules::Kind::MonteCarlo) continue;
        const compiler::Program pg = compiler::lower(gg, compiler::uniform_schedule(gg, rule));
        const compiler::Program pc = compiler::lower(gc, compiler::uniform_schedule(gc, rule));
        ASSERT_EQ(pg.input_names, pc.input_names) << name;
        const auto a = run(pg, n), b = run(pc, n);
        int bad = 0;
        for (std::size_t k = 0; k < a.size(); ++k)
          for (int i = 0; i < n; ++i) {
            const bool ok = std::fabs(a[k][i] - b[k][i]) <= 1e-6 * std::max(1.0f, std::fabs(b[k][i])) ||
                            (std::isnan(a[k][i]) && std::isnan(b[k][i]));
            if (!ok && bad++ < 3)
              ADD_FAILURE() << name << " fx " << fxi << " rule " << rules::to_string(rule) << " output " << k
                            << " pixel " << i << ": GLSL " << a[k][i] << " C++ " << b[k][i];
          }
      }
    }
  }
}

TEST(GlslSuite, NativeEvaluationEqualsTheCppTemplates) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(-6, 6), T(0, 3);
  for (const std::string& name : shaders::base_shader_names()) {
    const auto glsl_def = glsl::load_shader(std::string(BL_SCENES_DIR) + "/glsl/" + name + ".glsl");
    const shaders::ShaderDef& cpp_def = shaders::find_shader(name);
    shaders::Effects fx;
    fx.animated = true;
    fx.parallax = shaders::Parallax::Ripples;
    fx.lighting = shaders::Lighting::Phong;
    for (int i = 0; i < 2000; ++i) {
      shaders::Inputs<float> in{U(rng), U(rng), T(rng), {0.3f, -0.2f, 0.933f}, {0.4f, 0.3f, 0.866f}};
      const auto a = shaders::shade(*glsl_def, fx, in), b = shaders::shade(cpp_def, fx, in);
      ASSERT_NEAR(a.x, b.x, 1e-6f * std::max(1.0f, std::fabs(b.x))) << name << " " << in.u << " " << in.v;
      ASSERT_NEAR(a.y, b.y, 1e-6f * std::max(1.0f, std::fabs(b.y))) << name;
      ASSERT_NEAR(a.z, b.z, 1e-6f * std::max(1.0f, std::fabs(b.z))) << name;
    }
  }
}

}  // namespace
}  // namespace bl
