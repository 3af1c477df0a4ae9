// The whole generated include (generated/bandlimit.glsl) compiles and links on the headless driver
// (issue 14): Mesa refuses any static recursion ("has static recursion"), which glslangValidator
// reports only with -l. main() calls the entries that once reflected odd arguments by calling
// themselves (tan and tanh under box and tent) and a uniform-selected few others; the driver's
// recursion check covers every function of the shader.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace
