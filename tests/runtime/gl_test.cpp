// bl::gl::Context against CPU arithmetic: readback accuracy, pixel order, uniforms, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gl/egl_runner.hpp"
#include "gl/shader_log.hpp"

namespace {

using bl::gl::Context;

#define REQUIRE_GL()                                              \
  do {                                                            \
    const auto avail = Context::availability();                   \
    if (!avail.ok) GTEST_SKIP() << "no OpenGL: " << avail.reason; \
  } while (0)

constexpr const char* kShader = R"(#version 450 core
uniform float k;
uniform int n;
uniform vec2 offset;
uniform vec3 w;
uniform vec4 bias;
uniform mat3 m;
out vec4 color;
void main() {
  vec2 p = gl_FragCoord.xy + offset;
  color = vec4(sin(p.x * k), gl_FragCoord.y, dot(m * w, vec3(1.0, 2.0, 3.0)) + bias.z, float(n) + p.y);
}
)";

TEST(RuntimeGl, ReadbackMatchesCpuAndRowZeroIsTop) {
  REQUIRE_GL();
  Context gl;
  const int width = 67, height = 41;  // odd sizes: no accidental symmetry
  const float k = 0.1f, ox = 0.25f, oy = -3.0f;
  // m is column-major: columns (1,0,0), (0,2,0), (1,1,1); w = (1, 2, 3) so m*w = (4, 7, 3).
  const bl::gl::Mat3 m{{1, 0, 0, 0, 2, 0, 1, 1, 1}};
  const std::vector<bl::gl::Uniform> uniforms = {{"k", k},
                                                 {"n", 7},
                                                 {"offset", bl::gl::Vec2{ox, oy}},
                                                 {"w", bl::gl::Vec3{1, 2, 3}},
                                                 {"bias", bl::gl::Vec4{0, 0, 0.5f, 0}},
                                                 {"m", m}};
  const std::vector<float> px = gl.render(kShader, width, height, uniforms);
  ASSERT_EQ(px.size(), static_cast<size_t>(width * height * 4));
  const double dot_expected = 4.0 * 1 + 7.0 * 2 + 3.0 * 3 + 0.5;  // by hand from m, w and bias
  double worst = 0;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const float* p = &px[4 * (static_cast<size_t>(r) * width + c)];
      const double x = c + 0.5 + ox, y = r + 0.5 + oy;
      worst = std::max(worst, std::abs(p[0] - std::sin(x * k)));
      ASSERT_EQ(p[1], r + 0.5f) << "row " << r << " must see gl_FragCoord.y = row + 0.5";
      ASSERT_NEAR(p[2], dot_expected, 1e-5);
      ASSERT_NEAR(p[3], 7.0 + y, 1e-5);
    }
  }
  EXPECT_LE(worst, 1e-5);
  std::printf("[gl] %s: worst |sin| readback error %.3g\n", gl.renderer().c_str(), worst);
}

TEST(RuntimeGl, SyntaxErrorCarriesLogAndLine) {
  REQUIRE_GL();
  Context gl;
  const std::string bad = "#version 450 core\nout vec4 color;\nvoid main() {\n  color = vec4(1.0) +;\n}\n";
  try {
    gl.compile(bad);
    FAIL() << "a syntax error must throw";
  } catch (const bl::gl::ShaderError& e) {
    const std::string what = e.what();
    EXPECT_FALSE(e.log().empty());
    EXPECT_NE(what.find(e.log().substr(0, e.log().find('\n'))), std::string::npos) << what;
    EXPECT_NE(what.find("color = vec4(1.0) +;"), std::string::npos) << what;
    EXPECT_NE(what.find("fragment"), std::string::npos) << what;
  }
}

TEST(RuntimeGl, UnknownAndMistypedUniformsAreReported) {
  REQUIRE_GL();
  Context gl;
  const auto program = gl.compile(kShader);
  try {
    gl.render(program, 4, 4, {{"kk", 1.0f}});
    FAIL() << "a misspelled uniform must throw";
  } catch (const bl::gl::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'kk'"), std::string::npos) << what;
    EXPECT_NE(what.find("offset (vec2)"), std::string::npos) << what;  // lists what exists
  }
  try {
    gl.render(program, 4, 4, {{"w", 1.0f}});
    FAIL() << "a float given to a vec3 must throw";
  } catch (const bl::gl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("declared vec3"), std::string::npos) << e.what();
  }
  gl.set_unknown_uniform(bl::gl::UnknownUniform::kIgnore);
  EXPECT_NO_THROW(gl.render(program, 4, 4, {{"kk", 1.0f}}));
}

TEST(RuntimeGl, TimingAndProgramLifetime) {
  REQUIRE_GL();
  bl::gl::Program survivor;
  {
    Context gl;
    const auto program = gl.compile(kShader);
    const double ms = gl.time_ms(program, 512, 512, {{"k", 0.1f}}, 10);
    EXPECT_GT(ms, 0.0);
    EXPECT_TRUE(std::isfinite(ms));
    std::printf("[gl] 512x512 render: %.3f ms per frame\n", ms);
    survivor = gl.compile(kShader);
  }
  EXPECT_TRUE(survivor.valid());  // its context is gone: destroying it must be a no-op
}

TEST(RuntimeGl, BadSizeThrows) {
  REQUIRE_GL();
  Context gl;
  EXPECT_THROW(gl.render(kShader, 0, 16), bl::gl::Error);
}

TEST(RuntimeGlLog, ParsesMesaAndNvidiaLineNumbers) {
  EXPECT_EQ(bl::gl::shader_log_lines("0:4(20): error: syntax error\n0:2(1): warning: x\n0:4(3): error: y\n"),
            (std::vector<int>{4, 2}));
  EXPECT_EQ(bl::gl::shader_log_lines("0(12) : error C0000: syntax error"), (std::vector<int>{12}));
  EXPECT_EQ(bl::gl::shader_log_lines("ERROR: 0:3: 'x' : undeclared identifier"), (std::vector<int>{3}));
  const std::string annotated = bl::gl::annotate_shader_log("0:2(1): error: boom", "line one\nline two\n");
  EXPECT_NE(annotated.find("2 | line two"), std::string::npos) << annotated;
  EXPECT_EQ(annotated.find("line one"), std::string::npos) << annotated;
}

}  // namespace
