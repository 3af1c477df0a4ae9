// bl::jit and compiled frames: emitted C++ compiled at run time computes what the evaluator computes
// (plain, smoothed, MSAA), the object cache is hit the second time, compiler failures and a missing
// compiler are reported clearly; the counter-based MSAA jitter against hand-computed values.
#include "jit/jit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "camera/plane_batch.hpp"
#include "compiler/lower.hpp"
#include "jit/compiled_program.hpp"
#include "render/compiled_frame.hpp"
#include "render/frame.hpp"
#include "render/jitter.hpp"
#include "render/render.hpp"

namespace bl {
namespace {

std::string temp_cache(const std::string& name) {
  const auto p = std::filesystem::temp_directory_path() /
                 ("bl_jit_test_" + name + "_" +
                  std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  std::filesystem::create_directories(p);
  return p.string();
}

jit::Options opts(const std::string& cache) {
  jit::Options o;
  o.cache_dir = cache;
  return o;
}

TEST(Jit, CompilesLoadsAndHitsTheCacheTheSecondTime) {
  const std::string cache = temp_cache("cache");
  const std::string src = "extern \"C\" int bl_twice(int x) { return 2 * x; }\n";
  const auto first = jit::compile(src, opts(cache));
  EXPECT_FALSE(first->from_cache());
  auto twice = reinterpret_cast<int (*)(int)>(first->symbol("bl_twice"));
  EXPECT_EQ(twice(21), 42);
  const auto second = jit::compile(src, opts(cache));
  EXPECT_TRUE(second->from_cache());
  EXPECT_EQ(second->path(), first->path());
  EXPECT_EQ(reinterpret_cast<int (*)(int)>(second->symbol("bl_twice"))(5), 10);
  // Other flags are another object.
  jit::Options o2 = opts(cache);
  o2.flags = {"-O1", "-std=c++17"};
  EXPECT_NE(jit::cache_key(src, o2), jit::cache_key(src, opts(cache)));
  EXPECT_FALSE(jit::compile(src, o2)->from_cache());
  EXPECT_THROW(first->symbol("bl_absent"), jit::Error);
}

// The flags a cost model records: the options' own, else $BL_JIT_FLAGS, else the default, which
// targets the host (floorf is a library call on x86-64's baseline).
TEST(Jit, FlagsTextIsWhatCompilesThePrograms) {
  jit::Options o;
  o.flags = {"-O2", "-std=c++17"};
  EXPECT_EQ(jit::flags_text(o), "-O2 -std=c++17");
  if (!std::getenv("BL_JIT_FLAGS")) {
    EXPECT_EQ(jit::flags_text(), jit::kDefaultFlags);
    EXPECT_NE(std::string(jit::kDefaultFlags).find("-march=native"), std::string::npos);
  }
}

TEST(Jit, CompileErrorNamesTheFileAndShowsTheCompilerOutput) {
  const std::string cache = temp_cache("error");
  try {
    jit::compile("extern \"C\" int bl_bad() { return undeclared_name; }\n", opts(cache));
    FAIL() << "no error";
  } catch (const jit::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(cache), std::string::npos) << m;  // the source file
    EXPECT_NE(m.find(".cpp"), std::string::npos) << m;
    EXPECT_NE(m.find("undeclared_name"), std::string::npos) << m;  // the compiler's diagnostic
    EXPECT_NE(m.find("failed"), std::string::npos) << m;
  }
  jit::Options o = opts(cache);
  o.compiler = "/nonexistent/bl-cxx";
  try {
    jit::compile("int x;\n", o);
    FAIL() << "no error";
  } catch (const jit::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/bl-cxx"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

scene::Scene small_scene(const std::string& name) {
  scene::Scene s = scene::load_scene(std::string(BL_SCENES_DIR) + "/suite/" + name + ".json");
  s.width = s.height = 24;
  return s;
}

double max_abs_diff(const Image& a, const Image& b) {
  double d = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) d = std::max(d, std::fabs(double(a.at(x, y, c)) - b.at(x, y, c)));
  return d;
}

// The compiled program and the evaluator run the same float operations in the same order; -O3
// without -ffast-math keeps IEEE semantics (no FMA contraction on the default x86-64 target), so
// the images agree to rounding (1e-5 leaves room for a libm call inlined differently).
TEST(CompiledProgram, EqualsTheEvaluatorPlainSmoothedAndMsaa) {
  const std::string cache = temp_cache("shader");
  for (const std::string name : {"bricks_bumps"}) {
    const scene::Scene s = small_scene(name);
    const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
    const render::Frame f = render::frames(s).front();
    for (const char* rule : {"none", "gaussian"}) {
      const compiler::Program p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
      const jit::CompiledProgram cp(p, opts(cache));
      const Image a = render::render_program(s, f, p, render::compiled_runner(cp));
      const Image b = render::render_program(s, f, p, render::evaluator_runner(p));
      EXPECT_LT(max_abs_diff(a, b), 1e-5) << name << " " << rule;
      if (std::string(rule) == "gaussian") {
        EXPECT_LT(max_abs_diff(a, render::render_smoothed(s, f, p)), 1e-5) << name;
      } else {
        // MSAA of the compiled plain program at render_native's sample positions.
        const Image m = render::render_program(s, f, p, render::compiled_runner(cp), 4);
        EXPECT_LT(max_abs_diff(m, render::render_program(s, f, p, render::evaluator_runner(p), 4)), 1e-5);
        EXPECT_LT(max_abs_diff(m, render::render_native(s, f, 4)), 2e-3) << name;  // float offsets
        const render::FrameTiming t = render::time_program(s, f, p, render::compiled_runner(cp), 2, 2);
        EXPECT_GT(t.ns_per_pixel, 0);
        EXPECT_NEAR(t.ms_per_frame, t.ns_per_pixel * s.width * s.height * 1e-6, 1e-9);
      }
    }
  }
}

// A footprint-LOD pair (tuner/lod.hpp) in one compiled loop: each pixel gets the near program's
// colour where max(sigma_u, sigma_v) is below the limit and the far one's elsewhere, as the two
// programs compiled alone give them; a limit at the median footprint uses both.
TEST(CompiledProgram, FootprintLodPairPicksEachPixelsProgramByItsFootprint) {
  const std::string cache = temp_cache("lod");
  const scene::Scene s = small_scene("bricks_bumps");
  const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
  const render::Frame f = render::frames(s).front();
  const compiler::Program near = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
  const compiler::Program far =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  camera::PlaneBatch b;
  camera::trace_plane(render::make_camera(s, f.view), render::footprint_options(s), b);
  std::vector<float> fp;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.hit[i]) fp.push_back(std::max(b.sigma_u[i], b.sigma_v[i]));
  ASSERT_GT(fp.size(), 10u);
  std::nth_element(fp.begin(), fp.begin() + fp.size() / 2, fp.end());
  const float limit = fp[fp.size() / 2];
  const jit::CompiledProgram pair(near, far, limit, opts(cache));
  const jit::CompiledProgram cn(near, opts(cache)), cf(far, opts(cache));
  const Image img = render::render_program(s, f, near, render::compiled_runner(pair));
  const Image in = render::render_program(s, f, near, render::compiled_runner(cn));
  const Image ifar = render::render_program(s, f, far, render::compiled_runner(cf));
  int near_px = 0, far_px = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * s.width + x;
      if (!b.hit[i]) continue;
      const bool is_near = std::max(b.sigma_u[i], b.sigma_v[i]) < limit;
      (is_near ? near_px : far_px)++;
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(img.at(x, y, c), (is_near ? in : ifar).at(x, y, c)) << x << " " << y;
    }
  EXPECT_GT(near_px, 0);
  EXPECT_GT(far_px, 0);
  // Programs that do not pair: different inputs (a scene without parallax) or a bad limit.
  const scene::Scene flat = small_scene("bricks_none");
  const ir::Graph gf = shaders::trace(shaders::find_shader(flat.shader), flat.effects());
  const compiler::Program other =
      compiler::lower(gf, compiler::uniform_schedule(gf, rules::parse_rule("none")));
  EXPECT_THROW(jit::lod_batch_source(near, other, limit), std::invalid_argument);
  EXPECT_THROW(jit::lod_batch_source(near, far, -1.0f), std::invalid_argument);
  EXPECT_THROW(jit::lod_batch_source(near, far, NAN), std::invalid_argument);
}

// Values computed independently (Python, integer splitmix64 and math.log/cos/sin) from the
// definition in jitter.hpp.
TEST(Jitter, CounterBasedValuesMatchHandComputedOnes) {
  EXPECT_EQ(render::mix64(0), 0xe220a8397b1dcdafull);
  EXPECT_EQ(render::mix64(1), 0x910a2dec89025cc1ull);
  EXPECT_EQ(render::frame_key(1, 0, 0.0), 0x910a2dec89025cc1ull);
  EXPECT_EQ(render::frame_key(0xC0FFEE, 2, 1.5), 0x3302429d39fd9fc1ull);
  struct Case {
    std::uint64_t frame, pixel;
    std::uint32_t k;
    double sigma, x, y;
  };
  for (const Case& c :
       {Case{0x910a2dec89025cc1ull, 0, 0, 1.0, 0.30697299982669246, 0.38804367359922887},
        Case{0x910a2dec89025cc1ull, 12345, 7, 0.5, 0.49095496421657542, -0.17801293690601472},
        Case{0x3302429d39fd9fc1ull, 99, 31, 0.7, 0.11260084169031619, -0.45376632596367511}}) {
    const render::Offset o = render::gaussian_jitter(c.frame, c.pixel, c.k, c.sigma);
    EXPECT_NEAR(o.x, c.x, 1e-14);
    EXPECT_NEAR(o.y, c.y, 1e-14);
  }
}

TEST(Jitter, IsAStandardGaussianPerAxisAndReproducible) {
  const std::uint64_t key = render::frame_key(1, 0, 0.0);
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const render::Offset o = render::gaussian_jitter(key, i / 16, i % 16, 1.0);
    sx += o.x, sy += o.y, sxx += o.x * o.x, syy += o.y * o.y, sxy += o.x * o.y;
  }
  // 5 standard errors: mean sd 1/sqrt(n), variance sd sqrt(2/n).
  EXPECT_NEAR(sx / n, 0, 5 / std::sqrt(n));
  EXPECT_NEAR(sy / n, 0, 5 / std::sqrt(n));
  EXPECT_NEAR(sxx / n, 1, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(syy / n, 1, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sxy / n, 0, 5 / std::sqrt(n));
  const render::Offset a = render::gaussian_jitter(key, 77, 3, 0.5),
                       b = render::gaussian_jitter(key, 77, 3, 0.5);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
}

}  // namespace
}  // namespace bl
