// The emitted GLSL, executed on a headless OpenGL driver (Mesa llvmpipe), renders the same pixels
// as the C++ renderer's evaluator (max difference 1e-3 in display space). Skips, visibly, where no
// GL driver exists.
#include <gtest/gtest.h>

#include <cmath>

#include "compiler/lower.hpp"
#include "image/display.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"

namespace bl {
namespace {

TEST(GlslExec, MatchesTheCppRenderer) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  struct Case {
    const char* scene;
    const char* rule;
  };
  for (const Case c : {Case{"checkerboard_none", "dorn"}, Case{"circles_bumps", "dorn"},
                       Case{"quadratic_sine_ripples", "dorn"}, Case{"bricks_none", "gaussian"},
                       Case{"zigzag_bumps", "gaussian"}, Case{"fire_none", "box"}}) {
    scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR "/suite/") + c.scene + ".json");
    s.width = s.height = 64;
    const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
    const auto prog = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(c.rule)));
    for (const render::Frame& f : render::frames(s)) {
      const Image cpu = render::render_smoothed(s, f, prog);
      const Image gpu = render::render_glsl(ctx, s, f, prog);
      double worst = 0;
      for (std::size_t i = 0; i < cpu.pixels.size(); ++i)
        worst = std::max(worst, static_cast<double>(std::fabs(to_display(cpu.pixels[i]) - to_display(gpu.pixels[i]))));
      EXPECT_LE(worst, 1e-3) << c.scene << " / " << c.rule << " view " << f.view << " time " << f.time;
    }
  }
}

}  // namespace
}  // namespace bl
