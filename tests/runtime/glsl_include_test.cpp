// The whole generated include (generated/bandlimit.glsl) compiles and links on the headless driver
// (issue 14): Mesa refuses any static recursion ("has static recursion"), which glslangValidator
// reports only with -l. main() calls the entries that once reflected odd arguments by calling
// themselves (tan and tanh under box and tent) and a uniform-selected few others; the driver's
// recursion check covers every function of the shader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "bandlimit/table.hpp"
#include "gl/egl_runner.hpp"

namespace {

using bl::gl::Context;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GlslInclude, WholeIncludeCompilesOnTheDriver) {
  const auto avail = Context::availability();
  if (!avail.ok) GTEST_SKIP() << "no OpenGL: " << avail.reason;
  Context gl;
  std::string src = "#version 450 core\n" + read_file(BL_GENERATED_GLSL) +
                    "uniform vec2 v;\nout vec4 color;\nvoid main() {\n  float acc = 0.0;\n";
  for (const char* k : {"box", "tent"})
    for (const char* f : {"tan", "tan_sq", "tanh", "tanh_sq"})
      src += std::string("  acc += bl_") + k + "_" + f + "(v.x, v.y);\n";
  src += "  acc += bl_gaussian_fract(v.x, v.y) + bl_gaussian_step(v.x, v.y);\n";
  src += "  color = vec4(acc);\n}\n";
  EXPECT_NO_THROW({
    try {
      gl.compile(src);
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
      throw;
    }
  });
}

// The entries whose GLSL changed with issue 14 (the Gaussian periodic Fourier loop with
// recurrences, in place parity reflection), executed on the driver at x = -4 + i/8 and
// sigma = 0.01 + j/32 (exact in float, so both sides see the same inputs) against the C++ double
// entries: within the float bound 2e-5 max(1, |ref|).
TEST(GlslInclude, ChangedEntriesMatchTheCppTable) {
  const auto avail = Context::availability();
  if (!avail.ok) GTEST_SKIP() << "no OpenGL: " << avail.reason;
  Context gl;
  const int W = 64, H = 32;
  struct Quad {
    const char* glsl[4];
    double (*cpp[4])(double, double);
  };
  const Quad quads[] = {
      {{"bl_gaussian_fract", "bl_gaussian_floor_sq", "bl_tent_tanh", "bl_gaussian_triangle_sq"},
       {[](double x, double s) { return bl::gaussian::fract(x, s); },
        [](double x, double s) { return bl::gaussian::floor_sq(x, s); },
        [](double x, double s) { return bl::tent::tanh(x, s); },
        [](double x, double s) { return bl::gaussian::triangle_sq(x, s); }}},
      {{"bl_box_tan", "bl_tent_tan_sq", "bl_gaussian_trunc", "bl_gaussian_square"},
       {[](double x, double s) { return bl::box::tan(x, s); },
        [](double x, double s) { return bl::tent::tan_sq(x, s); },
        [](double x, double s) { return bl::gaussian::trunc(x, s); },
        [](double x, double s) { return bl::gaussian::square(x, s); }}},
      // The emitted straight-line Gaussian piecewise and exp-polynomial entries (emit_common.cpp).
      {{"bl_gaussian_smoothstep_sq", "bl_gaussian_abs", "bl_gaussian_laplace", "bl_gaussian_exp_ramp_sq"},
       {[](double x, double s) { return bl::gaussian::smoothstep_sq(x, s); },
        [](double x, double s) { return bl::gaussian::abs(x, s); },
        [](double x, double s) { return bl::gaussian::laplace(x, s); },
        [](double x, double s) { return bl::gaussian::exp_ramp_sq(x, s); }}},
      // Pulse trains' one-break regime and the box's antiderivative difference past 0.45 periods
      // (stop 26): sigma 0.01-1 spans both, x hits the breaks of square (multiples of 1/2).
      {{"bl_box_square", "bl_tent_square", "bl_box_pulse30", "bl_tent_pulse30_sq"},
       {[](double x, double s) { return bl::box::square(x, s); },
        [](double x, double s) { return bl::tent::square(x, s); },
        [](double x, double s) { return bl::box::pulse30(x, s); },
        [](double x, double s) { return bl::tent::pulse30_sq(x, s); }}},
      {{"bl_gaussian_saturate", "bl_gaussian_step", "bl_gaussian_exp_decay", "bl_gaussian_smoothstep"},
       {[](double x, double s) { return bl::gaussian::saturate(x, s); },
        [](double x, double s) { return bl::gaussian::step(x, s); },
        [](double x, double s) { return bl::gaussian::exp_decay(x, s); },
        [](double x, double s) { return bl::gaussian::smoothstep(x, s); }}},
  };
  const std::string lib = read_file(BL_GENERATED_GLSL);
  for (const Quad& q : quads) {
    std::string src = "#version 450 core\n" + lib + "out vec4 color;\nvoid main() {\n" +
                      "  float x = -4.0 + floor(gl_FragCoord.x) / 8.0;\n" +
                      "  float s = 0.01 + floor(gl_FragCoord.y) / 32.0;\n  color = vec4(";
    for (int c = 0; c < 4; ++c) src += std::string(c ? ", " : "") + q.glsl[c] + "(x, s)";
    src += ");\n}\n";
    const std::vector<float> px = gl.render(src, W, H, {});
    double worst[4] = {0, 0, 0, 0};
    for (int r = 0; r < H; ++r)
      for (int i = 0; i < W; ++i) {
        const double x = -4.0 + i / 8.0, s = static_cast<double>(0.01f + static_cast<float>(r) / 32.0f);
        for (int c = 0; c < 4; ++c) {
          const double ref = q.cpp[c](x, s);
          if (!std::isfinite(ref)) continue;  // a pole of tan
          const double got = px[4 * (static_cast<size_t>(r) * W + i) + c];
          const double e = std::fabs(got - ref) / std::max(1.0, std::fabs(ref));
          worst[c] = std::max(worst[c], std::isnan(e) ? 1.0 : e);
        }
      }
    for (int c = 0; c < 4; ++c) {
      EXPECT_LE(worst[c], 2e-5) << q.glsl[c];
      std::printf("[glsl] %-26s worst %.2g\n", q.glsl[c], worst[c]);
    }
  }
}

}  // namespace
