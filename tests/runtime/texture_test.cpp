// Texture nodes (clamped-domain paper, Section 4.3): the pyramids against brute-force sums over the
// level-0 texels (eqs. 21-22), GL's bilinear/trilinear rules at texel centres, the lowering of a
// texture node under each rule family, the smoothed lookup against supersampled ground truth, and
// scene errors that name the texture file.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "camera/plane_batch.hpp"
#include "compiler/emit.hpp"
#include "compiler/lower.hpp"
#include "image/metrics.hpp"
#include "render/frame.hpp"
#include "render/render.hpp"
#include "texture/sample.hpp"

namespace bl {
namespace {

// A 16x8 two-channel texture of values that are exact in float, irregular enough that any
// off-by-one texel shows.
texture::Level test_level() {
  texture::Level L;
  L.width = 16;
  L.height = 8;
  L.channels = 2;
  for (int y = 0; y < L.height; ++y)
    for (int x = 0; x < L.width; ++x) {
      L.texels.push_back(static_cast<float>((x * 7 + y * 13) % 11) / 8.0f);
      L.texels.push_back(static_cast<float>((x * x + 3 * y) % 5) / 4.0f);
    }
  return L;
}

TEST(TexturePyramid, LevelsAreBlockMeansOfLevelZero) {
  const texture::Level base = test_level();
  const texture::Pyramid p(base);
  ASSERT_EQ(p.levels(), 5);  // 16x8, 8x4, 4x2, 2x1, 1x1
  for (int k = 0; k < p.levels(); ++k) {
    const texture::Level& L = p.level(k);
    const int bx = base.width / L.width, by = base.height / L.height;  // level-0 texels per texel
    for (int y = 0; y < L.height; ++y)
      for (int x = 0; x < L.width; ++x)
        for (int c = 0; c < 2; ++c) {
          double sum = 0;
          for (int j = 0; j < by; ++j)
            for (int i = 0; i < bx; ++i) sum += base.at(x * bx + i, y * by + j, c);
          EXPECT_NEAR(L.at(x, y, c), sum / (bx * by), 1e-6) << "level " << k;
        }
  }
}

TEST(TexturePyramid, SamplingFollowsGlRules) {
  const texture::Pyramid p(test_level());
  // At a texel centre bilinear returns the texel; half-way between two it averages them; GL_REPEAT
  // wraps the left edge onto the right.
  for (int k = 0; k < p.levels(); ++k) {
    const texture::Level& L = p.level(k);
    for (int y = 0; y < L.height; ++y)
      for (int x = 0; x < L.width; ++x) {
        const float u = (x + 0.5f) / L.width, v = (y + 0.5f) / L.height;
        EXPECT_FLOAT_EQ(p.bilinear(k, u, v, 1), L.at(x, y, 1));
        EXPECT_FLOAT_EQ(p.trilinear(u, v, static_cast<float>(k), 1), L.at(x, y, 1));
        EXPECT_FLOAT_EQ(p.bilinear(k, u + 3.0f, v - 2.0f, 1), L.at(x, y, 1));  // whole periods
      }
  }
  const texture::Level& L0 = p.level(0);
  EXPECT_FLOAT_EQ(p.bilinear(0, 0.0f, 0.5f / 8, 0), 0.5f * (L0.at(0, 0, 0) + L0.at(15, 0, 0)));
  // Between levels: linear in lod.
  const float u = 0.3f, v = 0.6f;
  EXPECT_NEAR(p.trilinear(u, v, 1.25f, 0), 0.75f * p.bilinear(1, u, v, 0) + 0.25f * p.bilinear(2, u, v, 0),
              1e-6);
  // Clamped: below 0 (and NaN) level 0, above the top the 1x1 level.
  EXPECT_FLOAT_EQ(p.trilinear(u, v, -3.0f, 0), p.bilinear(0, u, v, 0));
  EXPECT_FLOAT_EQ(p.trilinear(u, v, std::nanf(""), 0), p.bilinear(0, u, v, 0));
  EXPECT_FLOAT_EQ(p.trilinear(u, v, 40.0f, 0), p.level(4).at(0, 0, 0));
}

TEST(TexturePyramid, StatIsTheFootprintsMeanAndVariance) {
  const texture::Level base = test_level();
  const texture::Texture t = texture::make_texture("t", "<test>", base);
  // A footprint whose lod is exactly 2 (4 s^2 + 2/3 = 16 texels^2), read at a level-2 texel
  // centre, covers that texel's 4x4 block of level 0: mean and population variance of those 16
  // values. (Isotropic: su = 16 texels/unit x s, sv = 8 texels/unit x the same s in texels.)
  const float s = std::sqrt((16.0f - 2.0f / 3.0f) / 4.0f);  // in texels
  EXPECT_NEAR(texture::lod_for_sd(s), 2.0f, 1e-6f);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const auto st = texture::sample_stat(t, (x + 0.5f) / 4, (y + 0.5f) / 2, s / 16, s / 8, 0);
      double m = 0, q = 0;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          const double p = base.at(4 * x + i, 4 * y + j, 0);
          m += p / 16;
          q += p * p / 16;
        }
      EXPECT_NEAR(st.mean, m, 1e-5);
      EXPECT_NEAR(st.var, q - m * m, 1e-5);
    }
  // A vanishing footprint reads level 0: the texel itself, variance 0 at its centre.
  const auto st = texture::sample_stat(t, 2.5f / 16, 3.5f / 8, 0.0f, 0.0f, 1);
  EXPECT_FLOAT_EQ(st.mean, base.at(2, 3, 1));
  EXPECT_NEAR(st.var, 0.0f, 1e-6);
}

// The anisotropic probes: along the long axis the lookup averages 4 probes whose spread makes up
// the variance the level lacks; on a texture that is linear in u (level 0: p = x / 16 per texel)
// any symmetric probe set returns the centre's value, and the variance grows with the long sd.
TEST(TexturePyramid, AnisotropicProbesKeepTheMean) {
  texture::Level L;
  L.width = 64;
  L.height = 64;
  L.channels = 1;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) L.texels.push_back(static_cast<float>(std::min(x, 40)));
  const texture::Texture t = texture::make_texture("ramp", "<test>", L);
  // Interior of the ramp, long axis u: symmetric probes on a linear function keep the mean.
  const float u = 20.5f / 64, v = 0.5f;
  const auto iso = texture::sample_stat(t, u, v, 0.5f / 64, 0.5f / 64, 0);
  const auto aniso = texture::sample_stat(t, u, v, 3.0f / 64, 0.5f / 64, 0);
  EXPECT_NEAR(iso.mean, 20.0f, 1e-3f);
  EXPECT_NEAR(aniso.mean, 20.0f, 1e-3f);
  // Variance of a linear ramp under the footprint: slope^2 * (s^2 + 1/6) with s = 3 texels, slope
  // 1 per texel; the probes are a 4-point rule, so this holds to the rule's accuracy for the quadratic.
  EXPECT_NEAR(aniso.var, 9.0f + 1.0f / 6.0f, 0.35f);
  // Long axis v: nothing changes along v, so the variance is the short axis' only.
  const auto along_v = texture::sample_stat(t, u, v, 0.5f / 64, 3.0f / 64, 0);
  EXPECT_NEAR(along_v.mean, 20.0f, 1e-3f);
  EXPECT_LT(along_v.var, 0.5f);
}

TEST(TexturePyramid, RejectsBadSizes) {
  texture::Level L;
  L.width = 12;
  L.height = 8;
  L.channels = 1;
  L.texels.assign(96, 0.0f);
  try {
    texture::make_texture("albedo", "odd.png", L);
    FAIL() << "a 12-texel side was accepted";
  } catch (const texture::TextureError& e) {
    EXPECT_NE(std::string(e.what()).find("odd.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("power of two"), std::string::npos) << e.what();
  }
}

scene::Scene textured_scene() {
  return scene::load_scene(BL_SCENES_DIR "/textures/textured_tiles.json");
}

TEST(TextureNode, LoweringPerRuleFamily) {
  const scene::Scene s = textured_scene();
  const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
  ASSERT_EQ(g.textures(), std::vector<std::string>{"albedo"});
  auto count = [&](const char* rule, compiler::LOp op) {
    const auto p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
    int n = 0;
    for (const auto& in : p.insts) n += in.op == op;
    return n;
  };
  EXPECT_EQ(count("none", compiler::LOp::TexPlain), 3);  // one direct lookup per channel
  EXPECT_EQ(count("none", compiler::LOp::TexStat), 0);
  EXPECT_EQ(count("gaussian", compiler::LOp::TexStat), 3);
  EXPECT_EQ(count("box", compiler::LOp::TexStat), 3);
  EXPECT_EQ(count("mc4", compiler::LOp::TexPlain), 12);  // 4 samples x 3 channels
  // The emitted C++ takes the textures; the GLSL declares two samplers.
  const auto p = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  EXPECT_NE(compiler::emit_cpp(p, "f").find("const bl::texture::Texture* const* bl_tex"), std::string::npos);
  const std::string glsl = compiler::emit_glsl(p, "f");
  EXPECT_NE(glsl.find("uniform sampler2D bl_tex0_mean;"), std::string::npos);
  EXPECT_NE(glsl.find("uniform sampler2D bl_tex0_sq;"), std::string::npos);
}

TEST(TextureNode, SmoothedLookupBeatsDirectSamplingAgainstTruth) {
  scene::Scene s = textured_scene();
  s.width = s.height = 64;
  s.truth_samples = 256;
  const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
  const render::Frame f = render::frames(s).front();
  const Image truth = render::render_truth(s, f, "");
  const Image plain = render::render_native(s, f, 0);
  const auto prog = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  const Image smooth = render::render_smoothed(s, f, prog);
  const double e_plain = rms_display(plain, truth), e_smooth = rms_display(smooth, truth);
  EXPECT_LT(e_smooth, 0.6 * e_plain) << "plain " << e_plain << " smoothed " << e_smooth;
  // Rule none is direct sampling: it equals the native render wherever the pixel filter lies wholly
  // on the plane or the sky (partly covered pixels at the horizon blend the two by coverage:
  // camera/horizon_coverage.hpp).
  const auto none = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
  const Image direct = render::render_smoothed(s, f, none);
  camera::PlaneBatch b;
  camera::trace_plane(render::make_camera(s, f.view), render::footprint_options(s), b);
  int partial = 0;
  double worst = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.coverage[i] > 0 && b.coverage[i] < 1) {
      ++partial;
      continue;
    }
    const int x = static_cast<int>(i % s.width), y = static_cast<int>(i / s.width);
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, double(std::fabs(direct.at(x, y, c) - plain.at(x, y, c))));
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_LE(partial, 3 * s.width);  // |distance to the horizon| < 3.1 s: 3 rows at s = 0.5 px
}

std::string temp_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("bl_texture_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}

std::string scene_with_texture(const std::string& dir, const std::string& file) {
  std::ifstream in(BL_SCENES_DIR "/textures/textured_tiles.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("albedo_cells.png");
  text.replace(at, std::string("albedo_cells.png").size(), file);
  const std::string path = dir + "/scene.json";
  std::ofstream(path) << text;
  return path;
}

void expect_error_naming(const std::string& scene_path, const std::string& needle, const std::string& also) {
  try {
    scene::load_scene(scene_path);
    FAIL() << "loaded a scene that should fail (" << needle << ")";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(also), std::string::npos) << e.what();
  }
}

TEST(TextureScene, BadTextureFilesAreNamed) {
  const std::string dir = temp_dir();
  // Missing file.
  expect_error_naming(scene_with_texture(dir, "nowhere.png"), "nowhere.png", "no such file");
  // Unreadable (not an image).
  std::ofstream(dir + "/garbage.png") << "not a png";
  expect_error_naming(scene_with_texture(dir, "garbage.png"), "garbage.png", "cannot read");
  // Four channels for a three-channel slot.
  {
    const std::string path = dir + "/rgba.png";
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(8, 8, 4, OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(out->open(path, spec));
    std::vector<unsigned char> px(8 * 8 * 4, 128);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
    out->close();
  }
  expect_error_naming(scene_with_texture(dir, "rgba.png"), "rgba.png", "4 channels");
  // A slot left unbound, and a slot the shader does not have.
  EXPECT_THROW(scene::parse_scene(R"({"shader": "textured_tiles"})"), std::invalid_argument);
  try {
    scene::parse_scene(R"({"shader": "checkerboard", "textures": {"albedo": "x.png"}})");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no such texture slot"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace bl

namespace bl {
namespace {

// Every pixel of a smoothed textured scene with parallax and lighting is finite (the tuner scores a
// non-finite pixel as an infinite error).
TEST(TextureNode, SmoothedBumpsSceneIsFinite) {
  scene::Scene s = scene::load_scene(BL_SCENES_DIR "/textures/textured_tiles_bumps.json");
  const ir::Graph g = shaders::trace(shaders::find_shader(s.shader), s.effects());
  for (const char* rule : {"gaussian", "dorn", "box"}) {
    const auto prog = compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule(rule)));
    for (const render::Frame& f : render::frames(s)) {
      const Image img = render::render_smoothed(s, f, prog);
      int bad = 0, first = -1;
      for (std::size_t i = 0; i < img.pixels.size(); ++i)
        if (!std::isfinite(img.pixels[i])) {
          if (first < 0) first = static_cast<int>(i);
          ++bad;
        }
      EXPECT_EQ(bad, 0) << rule << " view " << f.view << " first value " << first;
    }
  }
}

}  // namespace
}  // namespace bl
