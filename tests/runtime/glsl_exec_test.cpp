// The emitted GLSL, executed on a headless OpenGL driver (Mesa llvmpipe), renders the same pixels
// as the C++ renderer's evaluator (max difference 1e-3 in display space). Skips, visibly, where no
// GL driver exists.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bandlimit/registry.hpp"
#include "camera/plane_batch.hpp"
#include "compiler/emit.hpp"
#include "compiler/glsl_library.hpp"
#include "compiler/lower.hpp"
#include "compiler/supersample.hpp"
#include "image/display.hpp"
#include "render/frame.hpp"
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
  // Textured scenes upload the mean and mean-of-squares pyramids as two mipmapped samplers.
  for (const Case c : {Case{"suite/checkerboard_none", "dorn"}, Case{"suite/circles_bumps", "dorn"},
                       Case{"suite/quadratic_sine_ripples", "dorn"}, Case{"suite/bricks_none", "gaussian"},
                       Case{"suite/zigzag_bumps", "gaussian"}, Case{"suite/fire_none", "box"},
                       Case{"textures/textured_tiles", "none"}, Case{"textures/textured_tiles", "gaussian"},
                       Case{"textures/textured_tiles_bumps", "gaussian"}}) {
    scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR "/") + c.scene + ".json");
    s.width = s.height = 64;
    const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
    const auto prog = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(c.rule)));
    for (const render::Frame& f : render::frames(s)) {
      const Image cpu = render::render_smoothed(s, f, prog);
      const Image gpu = render::render_glsl(ctx, s, f, prog);
      double worst = 0;
      std::size_t over = 0;
      for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
        const double d = std::fabs(to_display(cpu.pixels[i]) - to_display(gpu.pixels[i]));
        worst = std::max(worst, d);
        over += d > 1e-3;
      }
      if (std::string(c.rule) == "none") {
        // Unsmoothed: a discontinuity (grout edge) one float rounding away from the sample flips a
        // value, and far away (|u| ~ 50) the GPU's u * width loses the bits our reduced coordinate
        // keeps, so a few values differ (measured: 1.5% over 1e-3 at 64x64, worst 0.09 in display);
        // the rest must agree. The smoothed cases below are held to 1e-3 everywhere.
        EXPECT_LE(over, cpu.pixels.size() / 33) << c.scene << " view " << f.view << " worst " << worst;
      } else {
        EXPECT_LE(worst, 1e-3) << c.scene << " / " << c.rule << " view " << f.view << " time " << f.time;
      }
    }
  }
}

// A footprint-LOD pair (compiler::emit_glsl_lod) on the driver against the C++ renderer's two
// programs chosen per pixel by the camera's footprint: near below the median footprint, far
// (Gaussian) above. Near is Dorn, or plain at 4 stratified samples (a supersampled near side, stop
// 36: it reads the inputs' screen gradients, which the far side does not). Pixels whose footprint
// rounds to the other side of the limit in the GPU's float camera may take the other program
// (allowed: 2% of them; llvmpipe: none for either near side at 64 x 64).
TEST(GlslExec, FootprintLodPairMatchesTheCppPrograms) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR "/") + "suite/bricks_bumps.json");
  s.width = s.height = 64;
  const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
  const auto far = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  const auto plain = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
  const render::Frame f = render::frames(s).front();
  camera::PlaneBatch b;
  camera::trace_plane(render::make_camera(s, f.view), render::footprint_options(s), b);
  std::vector<float> fp;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.hit[i]) fp.push_back(std::max(b.sigma_u[i], b.sigma_v[i]));
  ASSERT_GT(fp.size(), 100u);
  std::nth_element(fp.begin(), fp.begin() + fp.size() / 2, fp.end());
  const float limit = fp[fp.size() / 2];
  const Image cf = render::render_smoothed(s, f, far);
  for (const auto& [what, near] :
       {std::make_pair("dorn", compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("dorn")))),
        std::make_pair("ss4", compiler::stratified_samples(plain, 4, s.sigma_px))}) {
    SCOPED_TRACE(what);
    const gl::Program prog = ctx.compile(render::glsl_version_line() +
                                         compiler::emit_glsl_lod(near, far, limit, "bl_shade", "lod test") +
                                         "\n" + render::glsl_fragment_main(near, "bl_shade"));
    const Image gpu = render::render_glsl_compiled(ctx, s, f, near, prog);
    const Image cn = render::render_smoothed(s, f, near);
    std::size_t over = 0, near_px = 0, hit = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * s.width + x;
        if (!b.hit[i]) continue;
        ++hit;
        const bool is_near = std::max(b.sigma_u[i], b.sigma_v[i]) < limit;
        near_px += is_near;
        const Image& want = is_near ? cn : cf;
        double d = 0;
        for (int c = 0; c < 3; ++c)
          d = std::max(d, double(std::fabs(to_display(want.at(x, y, c)) - to_display(gpu.at(x, y, c)))));
        over += d > 1e-3;
      }
    std::printf("%s near: %zu of %zu hit pixels over 1e-3\n", what, over, hit);
    EXPECT_GT(near_px, 0u);
    EXPECT_LT(near_px, hit);
    EXPECT_LE(over, hit / 50) << "of " << hit;
  }
}

// The box/tent break sums (rulegen/emit_box_tent_breaks.cpp) of piecewise, periodic and staircase
// atomics: the GLSL print of the same description as the C++ one, executed, against the double
// table, at and beside breaks, on both sides of the periodic reduction's sign and across the
// hand-over widths (tent: the wide regime from sigma = 0.82).
// One fragment shader for a grid of calls: row r calls fns[r](x, s), pixel k of it at (xs[k % nx],
// ss[k / nx]); `value` is the call's GLSL type ("float" or "vec2") and `out` the vec4 written.
std::string grid_shader(const std::vector<std::string>& fns, const std::vector<float>& xs,
                        const std::vector<float>& ss, const std::string& value, const std::string& out) {
  auto list = [](const std::vector<float>& v) {
    std::ostringstream o;
    o.precision(9);
    for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << std::showpoint << v[i];
    return o.str();
  };
  const std::string nx = std::to_string(xs.size());
  std::string calls;
  for (std::size_t r = 0; r < fns.size(); ++r)
    calls += "  " + std::string(r ? "else " : "") + "if (row == " + std::to_string(r) + ") v = " + fns[r] +
             "(x, s);\n";
  return "#version 450\n" + compiler::glsl_library_slice(fns) + "const float xs[" + nx + "] = float[](" +
         list(xs) + ");\nconst float ss[" + std::to_string(ss.size()) + "] = float[](" + list(ss) +
         ");\nout vec4 o;\nvoid main() {\n  int k = int(gl_FragCoord.x), row = int(gl_FragCoord.y);\n  float "
         "x = "
         "xs[k % " +
         nx + "], s = ss[k / " + nx + "];\n  " + value + " v = " + value + "(0.0);\n" + calls +
         "  o = " + out + ";\n}\n";
}

// Runs every registry entry of `kernels` and `names` (convolutions of f and f^2) in GLSL at every
// (x, sigma) of the grid, one shader and one draw (compiling per entry took 20 s on llvmpipe: row r
// evaluates entry r, pixel k of it (xs[k % nx], ss[k / nx])), against the C++ double table.
// Returns the number of values checked.
int check_entries(gl::Context& ctx, const std::vector<std::string>& kernels,
                  const std::vector<std::string>& names, const std::vector<float>& xs,
                  const std::vector<float>& ss, double tol) {
  int n = 0;
  const auto* e = bl::registry::entries<double>(&n);
  int checked = 0;
  const int nx = static_cast<int>(xs.size()), ns = static_cast<int>(ss.size());
  std::vector<int> picked;
  std::vector<std::string> fns;
  for (int i = 0; i < n; ++i) {
    if (e[i].rule != std::string("convolution")) continue;
    if (std::find(kernels.begin(), kernels.end(), e[i].kernel) == kernels.end()) continue;
    if (std::find(names.begin(), names.end(), e[i].atomic->name) == names.end()) continue;
    picked.push_back(i);
    fns.push_back(e[i].glsl);
  }
  const int rows = static_cast<int>(picked.size());
  const gl::Program prog = ctx.compile(grid_shader(fns, xs, ss, "float", "vec4(v)"));
  const std::vector<float> px = ctx.render(prog, nx * ns, rows);  // row 0 = top
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < nx * ns; ++k) {
      const float x = xs[k % nx], s = ss[k / nx];
      const double want = e[picked[r]].smoothed(x, s);
      EXPECT_NEAR(px[4 * (r * nx * ns + k)], want, tol * std::max(1.0, std::fabs(want)))
          << fns[r] << " x=" << x << " s=" << s;
      ++checked;
    }
  return checked;
}

TEST(GlslExec, BoxTentBreakSums) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  const int checked =
      check_entries(ctx, {"box", "tent"},
                    {"fract", "square", "triangle", "floor", "ceil", "trunc", "abs", "sign", "step",
                     "saturate", "smoothstep"},
                    {-3.75f, -1.0f, -0.25f, -1e-6f, 0.0f, 0.25f, 0.5f, 0.999f, 1.0f, 2.75f, 37.5f},
                    {1e-3f, 0.1f, 0.5f, 0.8f, 1.0f, 3.0f}, 1e-4);
  EXPECT_GT(checked, 1000);
}

// The Gaussian periodic entries' straight-line GLSL (rulegen/emit_gauss_periodic.cpp, the C++ plan
// respelled) against the C++ double table, within blverify's float bound 2e-5: at, beside and between
// the breaks (period 1 and 2), on both sides of the signed reduction, at |x| up to 1e4, and at sigmas
// on both sides of every regime hand-over the float plans use (the emitted comments: 0.047 to 0.21;
// the staircases' narrow break sums below 0.088 / 0.175, trunc^2's mirrored form 0.25 to 3), down to
// 1e-6 and up to 30. (Setting BL_TAIL_CUT to 2 fails 1155 of these values.)
TEST(GlslExec, GaussianPeriodicStraightLine) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  const int checked =
      check_entries(ctx, {"gaussian"}, {"fract", "square", "triangle", "floor", "ceil", "trunc"},
                    {-1000.25f, -3.75f, -1.0f, -0.5f, -1e-6f, 0.0f, 1e-6f, 0.25f, 0.5f, 0.999f, 1.0f, 1.5f,
                     2.75f, 37.5f, 1e4f},
                    {1e-6f, 1e-3f,  0.03f,  0.045f, 0.05f,  0.07f,  0.09f, 0.095f, 0.1f, 0.104f,
                     0.15f, 0.18f,  0.19f,  0.2f,   0.21f,  0.25f,  0.35f, 0.5f,   1.0f, 3.0f,
                     30.0f, 0.087f, 0.088f, 0.174f, 0.176f, 0.249f, 2.5f,  3.01f},
                    2e-5);
  EXPECT_GT(checked, 2000);
}

// The Gaussian piecewise entries (straight-line break sums up to the narrowest piece's width, the
// generic per-piece sum past it) and every Gaussian piecewise and periodic entry at sigma = 0, where
// the GLSL returns f piece by piece without the piece table (a GPU builds such a table in local
// memory at every call site: NVIDIA's C5041, docs/gpu_timing.md): against the C++ double table at,
// beside and between the breaks, and across the hand-over (sigma 1 for saturate, 0.5 for abs).
TEST(GlslExec, GaussianPiecewiseAndSigmaZero) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  const int checked =
      check_entries(ctx, {"gaussian"},
                    {"abs", "sign", "step", "saturate", "smoothstep", "pulse30", "fract", "square",
                     "triangle", "floor", "ceil", "trunc"},
                    {-1000.25f, -3.75f, -1.0f, -0.5f, -1e-6f, 0.0f, 1e-6f, 0.25f, 0.3f, 0.5f, 0.999f, 1.0f,
                     1.5f, 2.75f, 37.5f},
                    {0.0f, 1e-3f, 0.1f, 0.499f, 0.501f, 0.999f, 1.001f, 1.5f, 3.0f, 30.0f}, 2e-5);
  EXPECT_GT(checked, 3000);
}

// The Gaussian periodic entries below sigma = 1e-30, where the C++ float entries hand over to the
// generic image sum and the GLSL keeps the straight-line block (no piece table: a GPU holds one in
// local memory per call site, docs/gpu_timing.md): at the breaks and a few sigma beside them, where
// the kernel still matters, against the C++ double table. A subnormal sigma (1e-39) is taken as
// FLT_MIN wide (a driver may also flush it to 0); away from the breaks (0, 0.3, 0.5, 1 and their
// periods) either must give f itself, never 0 * inf.
TEST(GlslExec, GaussianPeriodicTinySigma) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  const std::vector<std::string> names = {"fract", "square", "triangle", "pulse30", "floor", "ceil", "trunc"};
  int checked = check_entries(ctx, {"gaussian"}, names,
                              {-1.0f, -2e-36f, -1e-36f, 0.0f, 1e-37f, 1e-36f, 3e-36f, 1.0f, 0.5f, 37.5f},
                              {1e-36f, 2e-36f}, 2e-5);
  checked += check_entries(ctx, {"gaussian"}, names, {-1.0f, -1e-31f, 0.0f, 1e-31f, 0.5f, 1.0f, 2.75f},
                           {1e-31f, 3e-31f}, 2e-5);
  checked +=
      check_entries(ctx, {"gaussian"}, names, {-3.7f, -0.2f, 0.2f, 0.4f, 0.7f, 1.6f, 37.4f}, {1e-39f}, 2e-5);
  EXPECT_GT(checked, 250);
}

// The one-pass stat entries' GLSL ({E f, Var f} as vec2, rulegen/emit_stat_pairs.hpp, two channels
// of the same straight-line plan) against the C++ double stat entries: mean within 2e-5 max(1, |E f|),
// variance within 2e-5 max(1, E f^2), at and beside the breaks, across the plans' hand-overs (the
// emitted comments: 0.09 / 0.18 for fract and floor) and at the generic fallback (sigma 1e-31).
TEST(GlslExec, GaussianStatEntries) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  int n = 0;
  const auto* e = bl::registry::stat_entries<double>(&n);
  ASSERT_GE(n, 3);
  const std::vector<float> xs = {-1000.25f, -3.75f, -1.0f,  -1e-6f, 0.0f,  1e-6f,
                                 0.25f,     0.5f,   0.999f, 1.0f,   2.75f, 37.5f};
  const std::vector<float> ss = {1e-31f, 1e-6f, 1e-3f, 0.05f, 0.09f, 0.093f, 0.15f, 0.18f,
                                 0.19f,  0.24f, 0.25f, 0.33f, 0.5f,  1.0f,   3.0f,  30.0f};
  const int nx = static_cast<int>(xs.size()), ns = static_cast<int>(ss.size());
  std::vector<std::string> fns;
  for (int r = 0; r < n; ++r) fns.push_back(e[r].glsl);
  const gl::Program prog = ctx.compile(grid_shader(fns, xs, ss, "vec2", "vec4(v, 0.0, 1.0)"));
  const std::vector<float> px = ctx.render(prog, nx * ns, n);
  int checked = 0;
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < nx * ns; ++k) {
      const float x = xs[k % nx], s = ss[k / nx];
      const bl::stat<double> want = e[r].fn(x, s);
      const double m2 = want.var + want.mean * want.mean;
      const std::size_t at = 4 * (static_cast<std::size_t>(r) * nx * ns + k);
      EXPECT_NEAR(px[at], want.mean, 2e-5 * std::max(1.0, std::fabs(want.mean)))
          << fns[r] << " x=" << x << " s=" << s;
      EXPECT_NEAR(px[at + 1], want.var, 2e-5 * std::max(1.0, m2)) << fns[r] << " x=" << x << " s=" << s;
      ++checked;
    }
  EXPECT_EQ(checked, n * nx * ns);
}

// The Gaussian piecewise entries' GLSL (straight-line per break, the piece table built only for
// sigma = 0 and the generic wide-kernel code) against the C++ double table: at and beside the breaks
// (0, +-1 for saturate/smoothstep), far out, and across the hand-over to the generic code at the
// narrowest piece's width (saturate, smoothstep: 1, or 1/2 for degree > 3).
TEST(GlslExec, GaussianPiecewiseStraightLine) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  const int checked = check_entries(
      ctx, {"gaussian"}, {"abs", "sign", "step", "saturate", "smoothstep"},
      {-1e4f, -37.5f, -1.0f, -0.999f, -0.5f, -1e-6f, 0.0f, 1e-6f, 0.25f, 0.5f, 1.0f, 1.001f, 37.5f},
      {1e-6f, 1e-3f, 0.1f, 0.45f, 0.5f, 0.55f, 0.99f, 1.0f, 1.01f, 3.0f, 1e3f}, 2e-5);
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace bl

namespace bl {
namespace {

// The compact box/tent entries of the singular-at-0 atomics at tiny x (8.8e-21 came out of a
// saturate/pow chain in checkerboard_bumps): GLSL float used to return NaN there (the difference
// quotient underflows, and the unscaled Taylor coefficients overflow), where the C++ entries,
// which run in double, were finite. The GLSL must agree with the C++ double value.
TEST(GlslExec, CompactEntriesAtTinyArguments) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  int n = 0;
  const auto* e = bl::registry::entries<double>(&n);
  int checked = 0;
  for (int i = 0; i < n; ++i) {
    const std::string atomic = e[i].atomic->name;
    if (e[i].rule != std::string("convolution") ||
        !(e[i].kernel == std::string("box") || e[i].kernel == std::string("tent")))
      continue;
    if (atomic != "sqrt" && atomic != "log" && atomic != "inv" && atomic != "inv2") continue;
    const std::string src = "#version 450\n" + compiler::glsl_library_slice({e[i].glsl}) +
                            "uniform float x;\nuniform float s;\nout vec4 o;\nvoid main() { o = vec4(" +
                            e[i].glsl + "(x, s)); }\n";
    const gl::Program prog = ctx.compile(src);
    for (float x : {1e-30f, 8.8e-21f, 1e-18f, 3e-10f, 0.2f})
      for (float s : {1e-12f, 6.6e-12f, 1e-3f}) {
        const double want = e[i].smoothed(x, s);
        if (!(std::fabs(want) < 1e37)) continue;  // 1/x^2 at x = 1e-30: not a float, inf is right
        const float got = ctx.render(prog, 1, 1, {{"x", x}, {"s", s}})[0];
        // Relative, against the value's own size: these entries grow like 1/x or log x near 0.
        EXPECT_NEAR(got, want, 1e-4 * std::max(1.0, std::fabs(want)))
            << e[i].glsl << " x=" << x << " s=" << s;
        ++checked;
      }
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace bl
