// The fragment mains GPU timing runs (render/glsl_frame.hpp FragmentOptions), executed on the
// headless driver: a tiled target repeats the scene's image exactly, and supersampling in one
// fragment converges like the CPU renderer's MSAA (its own draws, the same kernel). Skips, visibly,
// where no GL driver exists.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "compiler/lower.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"

namespace bl {
namespace {

scene::Scene small_scene(const std::string& name, int size) {
  scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR "/suite/") + name + ".json");
  s.width = s.height = size;
  return s;
}

compiler::Program program(const scene::Scene& s, const char* rule) {
  const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
  return compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
}

Image draw(gl::Context& ctx, const scene::Scene& s, const compiler::Program& p, const render::FragmentOptions& o,
           int width, int height) {
  const gl::Program prog = ctx.compile(render::glsl_fragment_source(s, p, "450", o));
  ctx.set_unknown_uniform(gl::UnknownUniform::kIgnore);
  return image_from_rgba(ctx.render(prog, width, height, render::glsl_frame_uniforms(s, render::frames(s).front())),
                         width, height);
}

double rms(const Image& a, const Image& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::pow(double(a.pixels[i]) - b.pixels[i], 2);
  return std::sqrt(sum / a.pixels.size());
}

TEST(GlslSupersample, ATiledTargetRepeatsTheSceneImage) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  for (const int samples : {0, 4}) {
    const scene::Scene s = small_scene("checkerboard_ripples", 40);
    const compiler::Program p = program(s, samples > 0 ? "none" : "gaussian");
    render::FragmentOptions o;
    o.samples = samples;
    const Image one = draw(ctx, s, p, o, 40, 40);
    o.tiled = true;
    const Image tiled = draw(ctx, s, p, o, 120, 80);  // 3 x 2 tiles
    double worst = 0;
    for (int y = 0; y < 80; ++y)
      for (int x = 0; x < 120; ++x)
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, double(std::fabs(tiled.at(x, y, c) - one.at(x % 40, y % 40, c))));
    EXPECT_EQ(worst, 0.0) << "samples " << samples;
  }
}

// MSAA-16 drawn in one fragment lands as far from a 256-sample CPU render as the CPU's own MSAA-16
// does (same Gaussian kernel, independent draws), and much nearer than the plain shader.
TEST(GlslSupersample, SixteenSamplesInAFragmentConvergeLikeTheCpuMsaa) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  for (const char* name : {"circles_none", "zigzag_bumps"}) {
    const scene::Scene s = small_scene(name, 64);
    const render::Frame f = render::frames(s).front();
    const Image reference = render::render_native(s, f, 256);
    const compiler::Program plain = program(s, "none");
    render::FragmentOptions o;
    const double e_plain = rms(draw(ctx, s, plain, o, 64, 64), reference);
    o.samples = 16;
    const double e_gpu = rms(draw(ctx, s, plain, o, 64, 64), reference);
    const double e_cpu = rms(render::render_native(s, f, 16), reference);
    EXPECT_GT(e_gpu, 0.7 * e_cpu) << name;
    EXPECT_LT(e_gpu, 1.4 * e_cpu) << name;
    EXPECT_LT(e_gpu, 0.6 * e_plain) << name;
  }
}

}  // namespace
}  // namespace bl
