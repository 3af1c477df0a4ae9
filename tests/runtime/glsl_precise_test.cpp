// A hash (a sin or cos times a constant of magnitude >= 1024) has its argument emitted as GLSL that
// computes as written: `precise` on every instruction the argument is computed from, up to a step
// (a comparison, a plain floor / step / ...), and on the library functions those call. On NVIDIA's
// driver without it the smoothed programs of the value-noise and Voronoi patterns drew other noises
// than their plain programs (docs/gpu_timing.md, stops 41 and 42); that driver is not here, so these
// tests check what is emitted, that it compiles, and that it still computes what the C++ evaluator
// computes (on the GL driver there is, llvmpipe in CI).
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <regex>
#include <string>

#include "compiler/emit.hpp"
#include "compiler/functions.hpp"
#include "compiler/glsl_library.hpp"
#include "compiler/lower.hpp"
#include "dsl/math.hpp"
#include "image/display.hpp"
#include "render/frame.hpp"
#include "render/glsl_frame.hpp"
#include "render/render.hpp"
#include "shaders/shader.hpp"

namespace bl {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) ++n;
  return n;
}

// The program's own declarations "  precise float t<N> = " (the library's locals have other names).
std::size_t precise_instructions(const std::string& glsl) {
  static const std::regex decl(R"(\n  precise (float|vec2) t[0-9]+ = )");
  return static_cast<std::size_t>(
      std::distance(std::sregex_iterator(glsl.begin(), glsl.end(), decl), std::sregex_iterator()));
}

// Declarations that begin a statement inside braces get `precise`; parameters, for-loop headers,
// struct members, top-level constants and non-float types do not (GLSL allows no qualifier on a
// struct member, and a top-level constant computes nothing at run time).
TEST(GlslPrecise, DeclarationsInBodiesOnly) {
  const std::string in =
      "struct S { float a; vec2 b; };\n"
      "const float K = 2.0;\n"
      "float f(float x, vec2 y) {\n"
      "  float a = x * K, b = y.x;\n"
      "  int n = 3;\n"
      "  for (float t = 0.0; t < 1.0; t += 0.5) { vec3 c = vec3(t); a += c.x; }\n"
      "  if (a > b) { mat2 m = mat2(1.0); a = m[0][0]; } else a = 0.0;\n"
      "  S s; s.a = a;\n"
      "  return a + float(n);\n"
      "}\n";
  const std::string want =
      "struct S { float a; vec2 b; };\n"
      "const float K = 2.0;\n"
      "float f(float x, vec2 y) {\n"
      "  precise float a = x * K, b = y.x;\n"
      "  int n = 3;\n"
      "  for (float t = 0.0; t < 1.0; t += 0.5) { precise vec3 c = vec3(t); a += c.x; }\n"
      "  if (a > b) { precise mat2 m = mat2(1.0); a = m[0][0]; } else a = 0.0;\n"
      "  S s; s.a = a;\n"
      "  return a + float(n);\n"
      "}\n";
  EXPECT_EQ(compiler::precise_declarations(in), want);
}

ir::Graph hash_graph(double gain) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true), v = dsl::Var::input("v", true);
  const dsl::Var h = dsl::fract(dsl::sin(dsl::floor(u) * 127.1 + dsl::floor(v) * 311.7) * gain);
  g.add_output("r", (h * dsl::fract(u)).id());
  return g;
}

compiler::Program gaussian(const ir::Graph& g) {
  return compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
}

// The declaration of t<N> in a program's GLSL: "precise float", "float" ("" when absent).
std::string declaration_of(const std::string& glsl, const std::string& what) {
  const std::regex line("\\n  ((precise )?(float|vec2)) t[0-9]+ = [^\\n]*" + what);
  std::smatch m;
  return std::regex_search(glsl, m, line) ? m[1].str() : "";
}

// The body of GLSL function `name` in `glsl` (from its definition to the closing brace at column 0).
std::string body_of(const std::string& glsl, const std::string& name) {
  const std::regex def("\\n(float|vec2|void) " + name + "\\(");
  std::smatch m;
  if (!std::regex_search(glsl, m, def)) return "";
  const std::size_t from = static_cast<std::size_t>(m.position(0));
  return glsl.substr(from, glsl.find("\n}\n", from) - from);
}

std::string glsl_name(const char* cpp) {
  const int f = compiler::find_function(cpp);
  return f < 0 ? std::string("(no ") + cpp + ")" : compiler::functions()[f].glsl;
}

// fract(sin(tent-smoothed fract(u) * 127.1) * 43758.5), the rest all-Gaussian: the smoothed fract
// is in the hash's argument (its mean), the outer Gaussian fract computes on the hash's value.
TEST(GlslPrecise, TheHashArgumentAndTheLibraryItCallsArePrecise) {
  ir::Graph g;
  dsl::Tracer t(g);
  const dsl::Var u = dsl::Var::input("u", true);
  const dsl::Var inner = dsl::fract(u), hash = dsl::sin(inner * 127.1) * 43758.5;
  g.add_output("r", dsl::fract(hash).id());
  compiler::Schedule sch = compiler::uniform_schedule(g, rules::parse_rule("gaussian"));
  sch[inner.id()] = rules::parse_rule("tent");
  const compiler::Program p = compiler::lower(g, sch);
  const std::string glsl = compiler::emit_glsl(p, "shade");
  const std::string tent = glsl_name("bl::tent::fract"), gauss = glsl_name("bl::gaussian::fract");
  EXPECT_EQ(declaration_of(glsl, tent + "\\("), "precise float") << glsl;
  EXPECT_EQ(declaration_of(glsl, "127\\.09"), "precise float") << glsl;  // the constant
  EXPECT_EQ(declaration_of(glsl, "43758"), "float") << glsl;             // the hash, not its argument
  EXPECT_GT(precise_instructions(glsl), 0u);
  EXPECT_LT(precise_instructions(glsl), p.insts.size()) << glsl;
  // The library: the argument's tent fract computes as written, the Gaussian fract of the hash not.
  const std::string fb = body_of(glsl, tent), sb = body_of(glsl, gauss);
  ASSERT_FALSE(fb.empty()) << glsl;
  ASSERT_FALSE(sb.empty()) << glsl;
  EXPECT_NE(fb.find("precise"), std::string::npos) << fb;
  EXPECT_EQ(sb.find("precise"), std::string::npos) << sb;
}

// The argument's chain stops at a step: plain floor's rounding matters only at its jumps, where the
// plain shader itself is a coin toss, so what floor reads is emitted as before.
TEST(GlslPrecise, TheChainStopsAtAStep) {
  const ir::Graph g = hash_graph(43758.5453);
  const compiler::Program plain =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
  const std::string glsl = compiler::emit_glsl(plain, "shade");
  const std::string floor = glsl_name("bl::plain::floor");
  EXPECT_EQ(declaration_of(glsl, floor + "\\(t0\\)"), "precise float") << glsl;
  EXPECT_EQ(declaration_of(glsl, "127\\.09"), "precise float") << glsl;
  EXPECT_EQ(declaration_of(glsl, "bl_m\\[0\\]"), "float") << glsl;  // floor's argument u
  EXPECT_EQ(declaration_of(glsl, glsl_name("bl::plain::sin") + "\\("), "float") << glsl;
  // A LOD pair with it and the all-Gaussian side: each side's chain, one library.
  const compiler::Program gauss = gaussian(g);
  const std::string lod = compiler::emit_glsl_lod(plain, gauss, 0.1f, "shade");
  EXPECT_EQ(precise_instructions(lod),
            precise_instructions(glsl) + precise_instructions(compiler::emit_glsl(gauss, "shade")))
      << lod;
}

TEST(GlslPrecise, NoHashNoPrecise) {
  // A gain below 1024 amplifies no last-bit difference into another value: emitted as before.
  EXPECT_EQ(count(compiler::emit_glsl(gaussian(hash_graph(1000.0)), "shade"), "precise"), 0u);
  // Under any rule: a smoothed sin times a large gain is a hash too (here of a varying argument).
  {
    ir::Graph g;
    dsl::Tracer t(g);
    const dsl::Var u = dsl::Var::input("u", true);
    g.add_output("r", dsl::fract(dsl::sin(u * 127.1) * 43758.5).id());
    const compiler::Program p = gaussian(g);
    const std::string cpp = compiler::emit_cpp(p, "shade", "", compiler::CppForm::Header);
    ASSERT_EQ(cpp.find("bl::plain::sin"), std::string::npos) << cpp;  // the sin is smoothed
    EXPECT_GT(precise_instructions(compiler::emit_glsl(p, "shade")), 0u);
  }
  // The gain's sign does not matter.
  EXPECT_EQ(count(compiler::emit_glsl(gaussian(hash_graph(-43758.5)), "shade"), "precise"),
            count(compiler::emit_glsl(gaussian(hash_graph(43758.5)), "shade"), "precise"));
}

// Every function of the compiler's table, sliced precise, compiles; and a hash program, precise,
// renders what the evaluator renders (fbm_noise, a user's value noise in GLSL: four octaves of
// hashed lattice corners, all-Gaussian). Not to 1e-3 everywhere as other programs: the driver's sin
// and the C++ sinf differ in their last bits, which the hash's gain makes up to ~0.005 in display
// (llvmpipe, 64 x 64: worst 0.0055); another noise would be O(0.1) off at most pixels.
TEST(GlslPrecise, LibraryCompilesAndHashSceneMatchesTheEvaluator) {
  const auto av = gl::Context::availability();
  if (!av.ok) GTEST_SKIP() << "no OpenGL driver: " << av.reason;
  gl::Context ctx;
  std::vector<std::string> all;
  for (const compiler::Function& f : compiler::functions()) all.push_back(f.glsl);
  EXPECT_NO_THROW(ctx.compile("#version 450\n" + compiler::glsl_library_slice(all, all) +
                              "out vec4 o;\nvoid main() { o = vec4(0.0); }\n"));

  scene::Scene s = scene::load_scene(BL_SCENES_DIR "/glsl/fbm_noise.json");
  s.width = s.height = 64;
  const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
  const compiler::Program p = gaussian(g);
  ASSERT_NE(compiler::emit_glsl(p, "shade").find("precise"), std::string::npos);
  for (const render::Frame& f : render::frames(s)) {
    const Image cpu = render::render_smoothed(s, f, p);
    const Image gpu = render::render_glsl(ctx, s, f, p);
    double worst = 0, sq = 0;
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
      const double d = std::fabs(double(to_display(cpu.pixels[i])) - to_display(gpu.pixels[i]));
      worst = std::max(worst, d);
      sq += d * d;
    }
    EXPECT_LE(worst, 0.02) << "view " << f.view;
    EXPECT_LE(std::sqrt(sq / cpu.pixels.size()), 1e-3) << "view " << f.view;
  }
}

}  // namespace
}  // namespace bl
