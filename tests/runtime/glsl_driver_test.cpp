// The front end against the OpenGL driver: a pattern file, wrapped in a main() that calls shade() on
// a grid of surface coordinates, is run by the driver's own GLSL compiler (Mesa's on this machine),
// and the graph the front end traced from the same file, evaluated natively, must give the same
// pixels. The driver is the independent reference for GLSL's semantics (column-major matrices,
// constructors, built-ins), not our reading of the specification.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "gl/egl_runner.hpp"
#include "glsl/native.hpp"
#include "glsl/prelude.hpp"
#include "glsl/trace.hpp"

namespace bl {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

constexpr int kSize = 96;
constexpr double kLo = -2.7, kHi = 3.1;  // surface coordinates spanned by the grid

struct Mismatch {
  int pixels = 0;    // pixels with a channel off by more than the tolerance
  double worst = 0;  // the largest difference
};

// Pixel (c, r) shades uv = kLo + (kHi - kLo) (c + 0.5, r + 0.5) / kSize at `time` both ways.
Mismatch compare_with_driver(gl::Context& ctx, const std::string& file_text, float time, double tol) {
  const glsl::Pattern p = glsl::trace_source(file_text, "pattern.glsl");
  const glsl::NativeProgram prog(p.graph);
  const std::string frag = "#version 450\n" + glsl::prelude() + "\n#line 1\n" +
                           glsl::without_version_line(file_text) +
                           "\nuniform float bl_time;\nout vec4 bl_colour;\nvoid main() {\n"
                           "  vec2 uv = " +
                           std::to_string(kLo) + " + " + std::to_string(kHi - kLo) + " * gl_FragCoord.xy / " +
                           std::to_string(kSize) +
                           ".0;\n"
                           "  bl_colour = vec4(shade(uv, bl_time), 1.0);\n}\n";
  const std::vector<float> px = ctx.render(frag, kSize, kSize, {{"bl_time", time}});
  Mismatch m;
  for (int r = 0; r < kSize; ++r)
    for (int c = 0; c < kSize; ++c) {
      const float u = static_cast<float>(kLo + (kHi - kLo) * (c + 0.5) / kSize);
      const float v = static_cast<float>(kLo + (kHi - kLo) * (r + 0.5) / kSize);
      float out[3];
      prog.run(u, v, time, nullptr, out);
      double worst = 0;
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::fabs(double(out[k]) - px[(r * kSize + c) * 4 + k]));
      m.worst = std::max(m.worst, worst);
      m.pixels += !(worst <= tol);
    }
  return m;
}

// The driver (skipped where there is none), leaving uniforms a pattern does not read alone.
class GlslDriver : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto av = gl::Context::availability();
    if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
    renderer_ = av.reason;
    ctx_ = std::make_unique<gl::Context>();
    ctx_->set_unknown_uniform(gl::UnknownUniform::kIgnore);  // most patterns do not read the time
  }
  // The traced graph and the driver agree on src at `time` within tol on all but `allowed` pixels.
  void expect_driver_agrees(const std::string& src, double tol, int allowed = 0, float time = 0.0f) {
    const Mismatch m = compare_with_driver(*ctx_, src, time, tol);
    EXPECT_LE(m.pixels, allowed) << "time " << time << ": worst difference " << m.worst << " (" << renderer_
                                 << ")";
  }
  std::unique_ptr<gl::Context> ctx_;
  std::string renderer_;
};

TEST_F(GlslDriver, MatricesTraceAsTheDriverRunsThem) {
  // Every matrix form the front end maps, on smooth functions (no pixel sits at a jump).
  const std::string src = R"(#version 450
mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }
vec3 shade(vec2 uv, float time) {
  vec2 p = rot(0.4 + 0.3 * time) * uv;
  vec2 q = uv * rot(-0.7);
  mat3 m = mat3(vec3(2.0, 0.2 * uv.x, 0.5), vec3(0.3, 3.0, 0.1 * uv.y), 1.0, 0.5, 4.0);
  vec3 w = transpose(m) * vec3(p, 1.0) + m * vec3(q, 0.5);
  mat2 a = mat2(m) * 0.5 + mat2(0.25);
  a *= rot(0.2);
  a[1][0] += 0.1 * q.y;
  q *= a;
  vec2 z = inverse(a) * q + inverse(m)[2].xy;
  mat2x3 n = mat2x3(1.0, 0.5, -0.5, 0.25, 1.0, 0.75);
  vec3 o = n * p + outerProduct(vec3(1.0, 2.0, 3.0), vec2(0.1, 0.2))[1] + mat3(a)[2];
  mat2 c = matrixCompMult(a, mat2(1.0, 2.0, 3.0, 4.0)) - mat2(mat3(0.5));
  float d = determinant(m) + determinant(c);
  return vec3(0.5 + 0.5 * sin(w.x + z.x + 0.1 * d), 0.5 + 0.5 * cos(w.y - w.z + c[0][1]),
              0.5 + 0.25 * sin(o.z + z.y + c[1][1] + o.x));
}
)";
  for (float time : {0.0f, 1.3f}) expect_driver_agrees(src, 2e-4, 0, time);
}

TEST_F(GlslDriver, TracedIndicesTraceAsTheDriverRunsThem) {
  const std::string src = R"(#version 450
const vec3 palette[5] = vec3[](vec3(0.9, 0.1, 0.1), vec3(0.1, 0.8, 0.2), vec3(0.2, 0.3, 0.9),
                               vec3(0.7, 0.7, 0.1), vec3(0.5));
vec3 shade(vec2 uv, float time) {
  int i = int(mod(floor(uv.x * 1.7 + uv.y), 5.0));
  float w[4] = float[](0.1, 0.2, 0.3, 0.4);
  int j = int(clamp(floor(uv.y + 2.0), 0.0, 3.0));
  w[j] = fract(uv.x);
  w[3 - j] *= 2.0;
  mat3 m = mat3(1.0, 0.5, 0.25, 0.1, 0.2, 0.3, 0.9, 0.8, 0.7);
  int c = int(clamp(floor(uv.x + 1.5), 0.0, 2.0));
  m[c].y = 0.5 * fract(uv.y);  // a traced index inside the target
  m[2 - c][c] -= 0.2;
  vec3 col = m[c];
  return 0.5 * palette[i] + 0.25 * vec3(w[0] + w[1], w[2], w[3]) + 0.25 * col + 0.1 * m[1];
}
)";
  expect_driver_agrees(src, 1e-5);
}

TEST_F(GlslDriver, StructsTraceAsTheDriverRunsThem) {
  const std::string src = R"(#version 450
struct Wave { vec2 dir; float freq; float amp; };
struct Mix { Wave waves[3]; vec3 base; mat2 turn; };
float height(Wave w, vec2 p) { return w.amp * sin(w.freq * dot(w.dir, p)); }
vec3 shade(vec2 uv, float time) {
  Mix m = Mix(Wave[3](Wave(vec2(1.0, 0.0), 2.0, 0.2), Wave(vec2(0.6, 0.8), 3.0, 0.15),
                      Wave(vec2(-0.8, 0.6), 5.0, 0.1)), vec3(0.3, 0.4, 0.5), mat2(0.8, 0.6, -0.6, 0.8));
  m.waves[2].amp *= 0.5;
  vec2 p = m.turn * uv;
  float h = 0.0;
  for (int i = 0; i < 3; i++) h += height(m.waves[i], p);
  return m.base + vec3(h, 0.5 * h, -h);
}
)";
  expect_driver_agrees(src, 1e-4);
}

TEST_F(GlslDriver, SwitchTracesAsTheDriverRunsIt) {
  const std::string src = R"(#version 450
vec3 shade(vec2 uv, float time) {
  int i = int(mod(floor(uv.x * 1.3 + 0.5 * uv.y), 5.0));
  vec3 c = vec3(0.1);
  switch (i) {
    case 0: c.r = 0.9; break;
    case 1: c.g = 0.8;
    case 3: c.b = 0.7 + 0.1 * sin(uv.y); break;
    case 2: return vec3(0.5, 0.25 * fract(uv.x), 0.0);
    default: c = vec3(0.3, 0.6, 0.9);
  }
  return c;
}
)";
  expect_driver_agrees(src, 1e-5);
}

// Polar angles: GLSL's atan(y, x) jumps by 2 pi on the negative x axis; a pixel within rounding of
// it may land on the other side. The driver's atan is a low-precision approximation (llvmpipe:
// 1.3e-4 off here; GLSL allows thousands of ulp), so this checks quadrants and argument order, and
// InverseTrigonometry (glsl_frontend_test) the values against <cmath>.
TEST_F(GlslDriver, InverseTrigonometryTracesAsTheDriverRunsIt) {
  const std::string src = R"(#version 450
vec3 shade(vec2 uv, float time) {
  float angle = atan(uv.y - 0.3, uv.x + 0.2);
  float r = length(uv);
  return vec3(0.5 + 0.15 * angle, 0.5 + 0.3 * atan(3.0 * uv.x - uv.y), 0.25 * (asin(0.3 * uv.x) + acos(0.3 * uv.y)));
}
)";
  expect_driver_agrees(src, 1e-3, 2);
}

// Nested loops after a traced break and continue of the outer loop.
TEST_F(GlslDriver, NestedLoopsWithTracedBreaksTraceAsTheDriverRunsThem) {
  const std::string src = R"(#version 450
vec3 shade(vec2 uv, float time) {
  float acc = 0.0, hits = 0.0;
  for (int i = 0; i < 4; i++) {
    if (uv.x < float(i) - 1.5) break;
    if (uv.y < float(i) - 2.0) continue;
    for (int j = 0; j < 3; j++) {
      float t = float(i * 3 + j);
      if (uv.y > t * 0.5 - 2.0) break;
      acc += t;
    }
    hits += 1.0;
  }
  return vec3(0.02 * acc, 0.2 * hits, 0.5);
}
)";
  expect_driver_agrees(src, 1e-5);
}

// asinh, acosh and atanh (through log in the front end) as the driver computes them.
TEST_F(GlslDriver, InverseHyperbolicFunctionsTraceAsTheDriverRunsThem) {
  const std::string src = R"(#version 450
vec3 shade(vec2 uv, float time) {
  return vec3(0.5 + 0.1 * asinh(5.0 * uv.x), 0.2 * acosh(1.0 + uv.y * uv.y), 0.5 + 0.2 * atanh(0.3 * uv.x));
}
)";
  expect_driver_agrees(src, 1e-4);
}

// The example patterns (scenes/glsl) without a large-gain hash: a pixel whose argument lies within rounding
// of a jump may land on the other side in one of them, so a few pixels may differ; a misread construct moves
// far more.
TEST_F(GlslDriver, ExamplePatternsTraceAsTheDriverRunsThem) {
  for (const char* name :
       {"rotated_tiles", "checkerboard", "circles", "color_circles", "bricks", "zigzag", "quadratic_sine",
        "fire", "rings", "stripes", "sunburst", "hex_tiles", "plaid", "log_spiral"}) {
    const std::string src = read(std::string(BL_SCENES_DIR) + "/glsl/" + name + ".glsl");
    ASSERT_FALSE(src.empty()) << name;
    const Mismatch m = compare_with_driver(*ctx_, src, 0.7f, 1e-3);
    EXPECT_LE(m.pixels, kSize * kSize / 200)
        << name << ": " << m.pixels << " of " << kSize * kSize << " pixels differ, worst " << m.worst;
  }
}

}  // namespace
}  // namespace bl
