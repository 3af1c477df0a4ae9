// Scenes naming a .glsl file: resolved against the scene's folder, traced at load, rendered plain,
// with MSAA and smoothed; the truth cache key follows the GLSL; errors name the scene and the field.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "compiler/lower.hpp"
#include "render/render.hpp"
#include "scene/scene.hpp"

namespace bl {
namespace {

namespace fs = std::filesystem;

// A fresh folder outside the repository (the shader must work with no rebuild).
fs::path temp_dir() {
  const fs::path d =
      fs::temp_directory_path() /
      ("bl_glsl_scene_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  fs::create_directories(d / "shaders");
  return d;
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

const char* kScene = R"({"shader": "shaders/stripes.glsl", "image": {"width": 12, "height": 10},
  "ground_truth": {"samples": 16}, "parallax": "none"})";

TEST(GlslScene, RendersAGlslFileFromOutsideTheRepository) {
  const fs::path dir = temp_dir();
  write(dir / "shaders" / "stripes.glsl",
        "#version 450\nvec3 shade(vec2 uv, float time) {\n  float s = step(0.5, fract(uv.x * 3.0 + uv.y));\n"
        "  return mix(vec3(0.1, 0.2, 0.8), vec3(0.9, 0.8, 0.1), s);\n}\n");
  write(dir / "scene.json", kScene);
  const scene::Scene s = scene::load_scene((dir / "scene.json").string());
  EXPECT_EQ(s.name, "stripes");
  EXPECT_EQ(s.shader_def().name, "stripes");
  const ir::Graph g = shaders::trace(s.shader_def(), s.effects());
  const compiler::Program prog =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  for (const render::Frame& f : render::frames(s)) {
    const Image plain = render::render_native(s, f, 0), msaa = render::render_native(s, f, 16);
    const Image smooth = render::render_smoothed(s, f, prog);
    // Finite, and the same mean colour as 16-sample MSAA (a tiny image is mostly aliased).
    double sum_s = 0, sum_m = 0;
    for (std::size_t i = 0; i < plain.pixels.size(); ++i) {
      ASSERT_TRUE(std::isfinite(plain.pixels[i]) && std::isfinite(msaa.pixels[i]) &&
                  std::isfinite(smooth.pixels[i]));
      sum_s += smooth.pixels[i];
      sum_m += msaa.pixels[i];
    }
    EXPECT_NEAR(sum_s / plain.pixels.size(), sum_m / plain.pixels.size(), 0.05);
  }
  // The truth cache key follows the GLSL text.
  const std::string key1 = render::truth_cache_path(s, render::frames(s)[0], "cache");
  write(dir / "shaders" / "stripes.glsl",
        "vec3 shade(vec2 uv, float time) { return vec3(step(0.5, fract(uv.x * 4.0))); }\n");
  const scene::Scene s2 = scene::load_scene((dir / "scene.json").string());
  EXPECT_NE(render::truth_cache_path(s2, render::frames(s2)[0], "cache"), key1);
  fs::remove_all(dir);
}

TEST(GlslScene, TheGlslCheckerboardRendersLikeTheBuiltIn) {
  const std::string glsl = std::string(BL_SCENES_DIR) + "/glsl/checkerboard.glsl";
  const std::string common =
      R"(, "image": {"width": 16, "height": 12}, "parallax": "ripples", "lighting": "phong",
    "times": [0, 0.5]})";
  const scene::Scene a = scene::parse_scene(R"({"shader": ")" + glsl + "\"" + common);
  const scene::Scene b = scene::parse_scene(R"({"shader": "checkerboard")" + common);
  const ir::Graph ga = shaders::trace(a.shader_def(), a.effects()),
                  gb = shaders::trace(b.shader_def(), b.effects());
  const rules::Rule rule = rules::parse_rule("gaussian");
  const compiler::Program pa = compiler::lower(ga, compiler::uniform_schedule(ga, rule));
  const compiler::Program pb = compiler::lower(gb, compiler::uniform_schedule(gb, rule));
  for (const render::Frame& f : render::frames(a)) {
    const Image x = render::render_native(a, f, 4), y = render::render_native(b, f, 4);
    for (std::size_t i = 0; i < x.pixels.size(); ++i) ASSERT_NEAR(x.pixels[i], y.pixels[i], 1e-5);
    const Image xs = render::render_smoothed(a, f, pa), ys = render::render_smoothed(b, f, pb);
    for (std::size_t i = 0; i < xs.pixels.size(); ++i) ASSERT_NEAR(xs.pixels[i], ys.pixels[i], 1e-5);
  }
}

// A GLSL texture slot binds like a built-in shader's: the GLSL textured_tiles renders as the C++ one
// (plain, MSAA and smoothed).
TEST(GlslScene, TextureSlotsRenderLikeTheBuiltIn) {
  const std::string tail = R"(, "geometry": {"uv_scale": 0.5}, "image": {"width": 16, "height": 12},
    "textures": {"albedo": ")" +
                           std::string(BL_SCENES_DIR) + "/textures/albedo_cells.png\"}}";
  const scene::Scene a = scene::parse_scene(R"({"shader": ")" + std::string(BL_SCENES_DIR) +
                                            "/glsl/textured_tiles.glsl\"" + tail);
  const scene::Scene b = scene::parse_scene(R"({"shader": "textured_tiles")" + tail);
  ASSERT_EQ(a.textures.size(), 1u);
  const ir::Graph ga = shaders::trace(a.shader_def(), a.effects()),
                  gb = shaders::trace(b.shader_def(), b.effects());
  const rules::Rule rule = rules::parse_rule("gaussian");
  const compiler::Program pa = compiler::lower(ga, compiler::uniform_schedule(ga, rule));
  const compiler::Program pb = compiler::lower(gb, compiler::uniform_schedule(gb, rule));
  for (const render::Frame& f : render::frames(a)) {
    const Image x = render::render_native(a, f, 4), y = render::render_native(b, f, 4);
    for (std::size_t i = 0; i < x.pixels.size(); ++i) ASSERT_NEAR(x.pixels[i], y.pixels[i], 1e-5);
    const Image xs = render::render_smoothed(a, f, pa), ys = render::render_smoothed(b, f, pb);
    for (std::size_t i = 0; i < xs.pixels.size(); ++i) ASSERT_NEAR(xs.pixels[i], ys.pixels[i], 1e-5);
  }
}

// Every example scene under scenes/glsl loads and traces (the five user-style patterns and the
// suite's *_none scenes in GLSL included).
TEST(GlslScene, ExampleScenesLoad) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(BL_SCENES_DIR "/glsl")) {
    if (e.path().extension() != ".json") continue;
    const scene::Scene s = scene::load_scene(e.path().string());
    EXPECT_TRUE(s.glsl) << e.path();
    EXPECT_GT(shaders::trace(s.shader_def(), s.effects()).size(), 10) << e.path();
    ++n;
  }
  EXPECT_GE(n, 14);
}

TEST(GlslScene, ErrorsNameTheSceneTheFieldAndTheGlslLine) {
  const fs::path dir = temp_dir();
  write(dir / "scene.json", kScene);
  auto message = [&] {
    try {
      scene::load_scene((dir / "scene.json").string());
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  std::string m = message();  // the file is missing
  EXPECT_NE(m.find("scene.json, field 'shader'"), std::string::npos) << m;
  EXPECT_NE(m.find("stripes.glsl does not exist"), std::string::npos) << m;
  write(dir / "shaders" / "stripes.glsl", "vec3 shade(vec2 uv, float time) {\n  return vec3(uv.x)\n}\n");
  m = message();
  EXPECT_NE(m.find("field 'shader'"), std::string::npos) << m;
  EXPECT_NE(m.find("stripes.glsl:3:"), std::string::npos) << m;  // glslang: at the next token
  write(dir / "shaders" / "stripes.glsl",
        "vec3 shade(vec2 uv, float time) {\n  if (uv.x < 0.0) discard;\n  return vec3(1.0);\n}\n");
  m = message();
  EXPECT_NE(m.find("stripes.glsl:2:19: unsupported discard"), std::string::npos) << m;
  EXPECT_THROW(scene::parse_scene(R"({"shader": "no_such_shader"})"), std::invalid_argument);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace bl
