// Scene files: every suite scene loads; bad files are rejected naming the culprit; a scene compiles
// and renders only the effects it names.
#include <gtest/gtest.h>

#include <filesystem>

#include "compiler/lower.hpp"
#include "render/render.hpp"
#include "image/metrics.hpp"
#include "scene/scene.hpp"

namespace bl {
namespace {

std::string error_of(const std::string& json) {
  try {
    scene::parse_scene(json, "test.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, RejectsBadInputNamingIt) {
  EXPECT_NE(error_of(R"({"shader": "nope"})").find("unknown shader 'nope'"), std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "colour": 1})").find("'colour'"), std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "parallax": "waves"})").find("'waves'"), std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "image": {"width": -3}})").find("image.width"), std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "camera": {"views": [{"yaw": "x"}]}})").find("camera.views[0].yaw"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "camera": {"position": [0, 0, -1]}})").find("camera.position"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", )").find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_of(R"({"parallax": "none"})").find("'shader'"), std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "geometry": {"type": "sphere"}})").find("sphere"), std::string::npos);
  EXPECT_NE(error_of(R"({"shader": "fire", "footprint": {"bound": "box"}})").find("footprint.bound"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"shader": "fire"})"), "");
  EXPECT_THROW(scene::load_scene("/nonexistent/scene.json"), std::invalid_argument);
}

TEST(Scene, SuiteFilesLoad) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(BL_SCENES_DIR "/suite")) {
    const scene::Scene s = scene::load_scene(e.path().string());
    EXPECT_EQ(s.name + ".json", e.path().filename().string());
    ++n;
  }
  EXPECT_EQ(n, 21);
}

bool has_input(const ir::Graph& g, const std::string& name) {
  for (const auto& in : g.inputs())
    if (in.name == name) return true;
  return false;
}

TEST(Scene, OnlyNamedEffectsAreCompiled) {
  const scene::Scene flat = scene::load_scene(BL_SCENES_DIR "/suite/quadratic_sine_none.json");
  scene::Scene bumps = flat;
  bumps.parallax = shaders::Parallax::Bumps;
  const ir::Graph gf = shaders::trace(shaders::find_shader(flat.shader), flat.effects());
  const ir::Graph gb = shaders::trace(shaders::find_shader(bumps.shader), bumps.effects());
  // No parallax: no view inputs and strictly fewer nodes (the bump nodes are absent).
  EXPECT_FALSE(has_input(gf, "view_z"));
  EXPECT_TRUE(has_input(gb, "view_z"));
  EXPECT_LT(gf.size(), gb.size());
  const auto prog = compiler::lower(gf, compiler::uniform_schedule(gf, rules::parse_rule("dorn")));
  for (const auto& name : prog.input_names) EXPECT_TRUE(name == "u" || name == "v" || name == "time") << name;

  // A static scene (one time) renders one time sample per view and compiles no time input, even
  // for an animated shader.
  scene::Scene still = flat;
  still.times = {0.5};
  EXPECT_FALSE(has_input(shaders::trace(shaders::find_shader(still.shader), still.effects()), "time"));
  EXPECT_EQ(render::frames(still).size(), still.views.size());
  EXPECT_TRUE(has_input(gf, "time"));  // the suite's quadratic_sine is animated
  EXPECT_EQ(render::frames(flat).size(), flat.views.size() * flat.times.size());
}

TEST(Scene, SmoothedRenderBeatsPlainAgainstTruth) {
  // Small render: the Dorn-smoothed checkerboard is closer to the 256-sample truth than 1 sample.
  scene::Scene s = scene::load_scene(BL_SCENES_DIR "/suite/checkerboard_none.json");
  s.width = s.height = 48;
  s.truth_samples = 256;
  const render::Frame f{0, 0.0};
  const Image truth = render::render_truth(s, f, "");
  const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
  const auto prog = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("dorn")));
  const double smooth = rms_display(render::render_smoothed(s, f, prog), truth);
  const double plain = rms_display(render::render_native(s, f, 0), truth);
  EXPECT_LT(smooth, 0.5 * plain);
}

// The footprint bound only sets a smoothed shader's input widths: the plain shader's jittered
// samples (the truth) are bit-identical under both bounds, so they share one truth cache key; the
// pixel filter's width (sigma_px) does change the truth and the key.
TEST(SceneTruthCache, TheFootprintBoundSharesTheTruthAndSigmaDoesNot) {
  const std::string common = R"({"shader": "zigzag", "image": {"width": 12, "height": 10}, "footprint": {)";
  const scene::Scene d = scene::parse_scene(common + R"("bound": "dorn"}})");
  const scene::Scene m = scene::parse_scene(common + R"("bound": "marginal"}})");
  const scene::Scene w = scene::parse_scene(common + R"("bound": "marginal", "sigma_px": 0.7}})");
  const render::Frame f = render::frames(d)[0];
  EXPECT_EQ(render::truth_cache_path(d, f, "c"), render::truth_cache_path(m, f, "c"));
  EXPECT_NE(render::truth_cache_path(w, f, "c"), render::truth_cache_path(m, f, "c"));
  const Image a = render::render_native(d, f, 8), b = render::render_native(m, f, 8);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (std::size_t i = 0; i < a.pixels.size(); ++i) ASSERT_EQ(a.pixels[i], b.pixels[i]) << i;
  // The default is the exact marginal (docs/tuning.md: it won on 19 of 21 suite scenes).
  EXPECT_EQ(scene::parse_scene(R"({"shader": "zigzag"})").footprint_bound, scene::FootprintBound::Marginal);
}

}  // namespace
}  // namespace bl
