// runtime/normalmap and image/ssim against independent references: brute-force quadrature over the
// angle and over slope space, constant maps (every filter must reduce to direct shading), a
// two-normal map (the multi-lobe cells must give the exact footprint mean), SSIM by a naive
// per-window sum and its closed form on constant images, and bad input naming the file.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "image/ssim.hpp"
#include "normalmap/generate.hpp"
#include "normalmap/lobe.hpp"
#include "normalmap/nm_scene.hpp"
#include "normalmap/normal_data.hpp"
#include "normalmap/techniques.hpp"
#include "texture/texture.hpp"

using namespace bl;
using namespace bl::normalmap;

namespace {

// E[f(theta)], theta ~ N(mu, sigma^2), by the trapezoid rule on a fine grid over mu +- 10 sigma.
template <class F>
double brute_expect(F f, double mu, double sigma, int n = 200000) {
  const double a = mu - 10 * sigma, b = mu + 10 * sigma, h = (b - a) / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = a + i * h, z = (t - mu) / sigma;
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    s += w * f(t) * std::exp(-0.5 * z * z);
  }
  return s * h / (sigma * std::sqrt(2 * M_PI));
}

texture::Level encoded_level(int w, int h, const std::vector<V3>& normals_by_parity) {
  texture::Level l{w, h, 3, std::vector<float>(std::size_t(w) * h * 3)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const V3 n = normalize(normals_by_parity[(x + y) % normals_by_parity.size()]);
      const double e[3] = {n.x, n.y, n.z};
      for (int c = 0; c < 3; ++c) l.texels[(std::size_t(y) * w + x) * 3 + c] = float(0.5 * e[c] + 0.5);
    }
  return l;
}

NmScene test_scene(Model model) {
  NmScene s;
  s.material.model = model;
  s.material.exponent = 32;
  s.material.alpha = 0.25;
  s.light.dir = normalize({0.5, 0.2, 0.8});
  return s;
}

std::string tmp_dir() {
  const auto d = std::filesystem::temp_directory_path() / "bl_normalmap_test";
  std::filesystem::create_directories(d);
  return d.string();
}

}  // namespace

TEST(Ssim, IdenticalImagesGiveOne) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(40 * 30);
  for (double& v : x) v = u(rng);
  EXPECT_NEAR(ssim(x, x, 40, 30), 1.0, 1e-12);
}

TEST(Ssim, ConstantImagesMatchTheClosedForm) {
  // No variance: SSIM = (2ab + C1) / (a^2 + b^2 + C1) at every window.
  const double a = 0.3, b = 0.5, c1 = 1e-4;
  const std::vector<double> x(20 * 20, a), y(20 * 20, b);
  EXPECT_NEAR(ssim(x, y, 20, 20), (2 * a * b + c1) / (a * a + b * b + c1), 1e-12);
}

TEST(Ssim, MatchesANaivePerWindowSum) {
  const int w = 23, h = 17;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(w * h), y(w * h);
  for (int i = 0; i < w * h; ++i) x[i] = u(rng), y[i] = 0.6 * x[i] + 0.4 * u(rng);
  double kern[11][11], ks = 0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j)
      ks += kern[i][j] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2 * 2.25));
  double total = 0;
  int count = 0;
  for (int y0 = 0; y0 + 11 <= h; ++y0)
    for (int x0 = 0; x0 + 11 <= w; ++x0) {
      double mx = 0, my = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          const double k = kern[i][j] / ks;
          mx += k * x[(y0 + i) * w + x0 + j], my += k * y[(y0 + i) * w + x0 + j];
        }
      double vx = 0, vy = 0, cxy = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          const double k = kern[i][j] / ks, dx = x[(y0 + i) * w + x0 + j] - mx,
                       dy = y[(y0 + i) * w + x0 + j] - my;
          vx += k * dx * dx, vy += k * dy * dy, cxy += k * dx * dy;
        }
      total += (2 * mx * my + 1e-4) * (2 * cxy + 9e-4) / ((mx * mx + my * my + 1e-4) * (vx + vy + 9e-4));
      ++count;
    }
  std::vector<double> map;
  EXPECT_NEAR(ssim(x, y, w, h, &map), total / count, 1e-10);
  EXPECT_EQ(int(map.size()), count);
  EXPECT_THROW(ssim(x, y, 10, 10), std::invalid_argument);
}

TEST(Lobe, GaussHermiteMoments) {
  for (int n : {8, 16, 32, 64}) {
    const Quadrature& q = gauss_hermite(n);
    double m0 = 0, m2 = 0, m4 = 0;
    for (int i = 0; i < n; ++i)
      m0 += q.w[i], m2 += q.w[i] * q.x[i] * q.x[i], m4 += q.w[i] * std::pow(q.x[i], 4);
    EXPECT_NEAR(m0, 1, 1e-12) << n;
    EXPECT_NEAR(m2, 1, 1e-11) << n;
    EXPECT_NEAR(m4, 3, 1e-10) << n;
  }
}

TEST(Lobe, CosPowerClosedFormMatchesBruteForce) {
  for (int s : {1, 8, 33, 64, 200})
    for (double mu : {0.0, 0.1, 0.4, 0.9})
      for (double sigma : {0.01, 0.05, 0.2, 0.5}) {
        const auto coef = cos_power_coefficients(s);
        const double ref = brute_expect([&](double t) { return std::pow(std::cos(t), s); }, mu, sigma);
        EXPECT_NEAR(expected_cos_power(coef, s, mu, sigma), ref, 1e-9 + 1e-7 * ref)
            << "s " << s << " mu " << mu << " sigma " << sigma;
      }
  // sigma = 0 is direct shading.
  const auto coef = cos_power_coefficients(64);
  EXPECT_NEAR(expected_cos_power(coef, 64, 0.3, 0.0), std::pow(std::cos(0.3), 64), 1e-14);
}

TEST(Lobe, GgxExpectationMatchesBruteForce) {
  for (double alpha : {0.1, 0.15, 0.25, 0.5})
    for (double mu : {0.0, 0.03, 0.15, 0.37, 0.5, 1.1})
      for (double sigma : {0.02, 0.049, 0.08, 0.2, 0.4, 0.7}) {
        const double ref = brute_expect(
            [&](double t) { return std::fabs(t) < 0.5 * M_PI ? ggx_d(std::cos(t), alpha) : 0.0; }, mu, sigma);
        const double got = expected_ggx_d(mu, sigma, alpha);
        // Gauss-Hermite (narrow footprints) or the interpolated table (wide ones): within 2%, or
        // 0.2% of the lobe's peak where the expectation is tiny.
        EXPECT_NEAR(got, ref, 0.02 * ref + 0.002 * ggx_d(1, alpha))
            << "alpha " << alpha << " mu " << mu << " sigma " << sigma;
      }
}

TEST(Lobe, LeanBeckmannMatchesNumericalConvolution) {
  // A Gaussian distribution of bump slopes N(mean, S); the micro-surface's Beckmann slopes add, so
  // the footprint's slope density is the convolution, integrated here on a grid.
  const double m = 0.3, bx = 0.1, by = -0.05, sxx = 0.04, syy = 0.02, sxy = 0.012;
  const float mom[5] = {float(bx), float(by), float(sxx + bx * bx), float(syy + by * by),
                        float(sxy + bx * by)};
  const SlopeStats st = slope_stats(mom);
  const double det = sxx * syy - sxy * sxy;
  auto bump = [&](double x, double y) {
    const double dx = x - bx, dy = y - by;
    return std::exp(-0.5 * (syy * dx * dx - 2 * sxy * dx * dy + sxx * dy * dy) / det) /
           (2 * M_PI * std::sqrt(det));
  };
  auto beck = [&](double x, double y) { return std::exp(-(x * x + y * y) / (m * m)) / (M_PI * m * m); };
  for (auto [hx, hy] : {std::pair{0.0, 0.0}, std::pair{0.2, 0.1}, std::pair{-0.3, 0.25}}) {
    const int n = 600;
    const double lo = -2.0, hi = 2.0, h = (hi - lo) / n;
    double sum = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = lo + (i + 0.5) * h, y = lo + (j + 0.5) * h;
        sum += bump(x, y) * beck(hx - x, hy - y);
      }
    sum *= h * h;
    EXPECT_NEAR(lean_beckmann_p22(st, hx, hy, m), sum, 1e-6 * sum + 1e-9) << hx << " " << hy;
    // D(h) = P22(h~) / h_z^4 for the unit half vector with slope (hx, hy).
    const double hz = 1 / std::sqrt(1 + hx * hx + hy * hy);
    EXPECT_NEAR(lean_beckmann_d(st, hx * hz, hy * hz, hz, m), sum / std::pow(hz, 4),
                1e-6 * sum / std::pow(hz, 4));
  }
}

TEST(Lobe, LeanReducesToTheUnfilteredLobes) {
  const float flat[5] = {0, 0, 0, 0, 0};
  const SlopeStats st = slope_stats(flat);
  for (double t : {0.0, 0.1, 0.3}) {
    const double hx = std::sin(t), hz = std::cos(t);
    EXPECT_NEAR(lean_ggx_d(st, hx, 0, hz, 0.2), ggx_d(hz, 0.2), 1e-9 * ggx_d(hz, 0.2));
  }
  EXPECT_NEAR(lean_blinn_phong(st, 0, 0, 1, 64), 1.0, 1e-12);  // peak of the unnormalized lobe
}

TEST(Techniques, ConstantMapEqualsDirectShading) {
  // A constant normal map: every level's averaged normal is the normal itself (|N| = 1), so
  // Toksvig's and eqs. 24-25's spread vanish and both reduce to direct shading at any footprint.
  const V3 n = normalize({0.25, -0.1, 0.95});
  const NormalMapData d = build_normal_map(encoded_level(16, 16, {n}), "<constant>", LobeGrid{});
  const V3 nd = normalize(
      {d.normals.level(0).at(0, 0, 0), d.normals.level(0).at(0, 0, 1), d.normals.level(0).at(0, 0, 2)});
  for (Model model : {Model::BlinnPhong, Model::GGX}) {
    const NmScene s = test_scene(model);
    const Shader sh(s, d);
    for (V3 view : {normalize({-0.6, 0.1, 0.5}), normalize({-0.9, 0.0, 0.2}), V3{0, 0, 1}})
      for (double sigma : {0.0, 0.01, 0.3, 10.0}) {
        const auto ref = sh.shade_normal(nd, view);
        Sample smp{0.3, 0.7, sigma, sigma, view};
        for (Technique t : {Technique::Direct, Technique::Toksvig, Technique::Ours, Technique::OursMulti}) {
          const auto got = sh.filtered(t, smp);
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], ref[c], 2e-4 * (1 + ref[c])) << technique_name(t) << " sigma " << sigma;
        }
      }
  }
}

TEST(Techniques, MultiLobeGivesTheExactMeanOfTwoNormals) {
  // A checkerboard of two normals in different cells: at the top level each cell holds one normal
  // (no spread), so the multi-lobe specular is the exact average of the two shadings.
  const V3 n1 = normalize({0.5, 0.1, 0.86}), n2 = normalize({-0.45, -0.2, 0.87});
  const NormalMapData d = build_normal_map(encoded_level(16, 16, {n1, n2}), "<checker>", LobeGrid{4, 2});
  const auto un = [&](int x) {
    return normalize(
        {d.normals.level(0).at(x, 0, 0), d.normals.level(0).at(x, 0, 1), d.normals.level(0).at(x, 0, 2)});
  };
  for (Model model : {Model::BlinnPhong, Model::GGX}) {
    NmScene s = test_scene(model);
    s.lobe_threshold = 0.0;
    const Shader sh(s, d);
    const V3 view = normalize({-0.3, -0.1, 0.9});
    const auto a = sh.shade_normal(un(0), view), b = sh.shade_normal(un(1), view);
    bool multi = false;
    const auto got = sh.filtered(Technique::OursMulti, Sample{0.5, 0.5, 100, 100, view}, &multi);
    EXPECT_TRUE(multi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], 0.5 * (a[c] + b[c]), 1e-4 * (1 + a[c] + b[c]));
  }
}

TEST(NormalData, LeanMomentsAverageLinearly) {
  const V3 n1 = normalize({0.3, 0.0, 0.9}), n2 = normalize({-0.1, 0.2, 0.95});
  const NormalMapData d = build_normal_map(encoded_level(8, 8, {n1, n2}), "<checker>", LobeGrid{});
  const texture::Level& top = d.lean.level(d.lean.levels() - 1);
  const texture::Level& l0 = d.lean.level(0);
  for (int c = 0; c < 5; ++c) EXPECT_NEAR(top.at(0, 0, c), 0.5 * (l0.at(0, 0, c) + l0.at(1, 0, c)), 1e-6);
  EXPECT_NEAR(l0.at(0, 0, 2), l0.at(0, 0, 0) * l0.at(0, 0, 0), 1e-6);
  // The cell shares of every texel sum to 1.
  const texture::Level& cells = d.lobes.level(1);
  double w = 0;
  for (int c = 0; c < d.grid.cells(); ++c) w += cells.at(0, 0, 4 * c);
  EXPECT_NEAR(w, 1.0, 1e-6);
}

TEST(NormalData, CommittedTexturesAreTheGeneratorsOutput) {
  for (auto [p, name] :
       {std::pair{Pattern::Rivets, "nm_rivets.png"}, std::pair{Pattern::Hammered, "nm_hammered.png"}}) {
    const std::string file = std::string(BL_SOURCE_DIR) + "/scenes/textures/" + name;
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    EXPECT_LT(std::filesystem::file_size(file), 1u << 20);
    const texture::Level gen = normal_map(p, 256);
    const texture::Texture t = texture::load_texture("normal", file, 3, texture::Encoding::Linear);
    ASSERT_EQ(t.mean.width(), gen.width);
    const texture::Level& l0 = t.mean.level(0);
    double worst = 0;
    for (std::size_t i = 0; i < gen.texels.size(); ++i)
      worst = std::max(worst, double(std::fabs(gen.texels[i] - l0.texels[i])));
    EXPECT_LT(worst, 1e-6) << name << ": regenerate with `cmake --build <build> --target normalmap_textures`";
  }
}

TEST(BadInput, MissingFileIsNamed) {
  const std::string file = tmp_dir() + "/no_such_normal_map.png";
  try {
    load_normal_map(file, LobeGrid{});
    FAIL() << "no error";
  } catch (const texture::TextureError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
}

TEST(BadInput, FourChannelFileIsNamed) {
  const std::string file = tmp_dir() + "/rgba_normal_map.png";
  std::vector<unsigned char> px(16 * 16 * 4, 200);
  auto out = OIIO::ImageOutput::create(file);
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file, OIIO::ImageSpec(16, 16, 4, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
  out->close();
  try {
    load_normal_map(file, LobeGrid{});
    FAIL() << "no error";
  } catch (const texture::TextureError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find("4 channels"), std::string::npos) << msg;
  }
}

TEST(BadInput, UnreadableFileIsNamed) {
  const std::string file = tmp_dir() + "/garbage_normal_map.png";
  { std::ofstream(file) << "not a png"; }
  try {
    load_normal_map(file, LobeGrid{});
    FAIL() << "no error";
  } catch (const texture::TextureError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
}

TEST(BadInput, BackFacingTexelIsNamed) {
  texture::Level l = encoded_level(4, 4, {V3{0, 0, 1}});
  l.texels[2] = 0.1f;  // texel (0, 0): n_z = -0.8
  try {
    build_normal_map(l, "flat.png", LobeGrid{});
    FAIL() << "no error";
  } catch (const texture::TextureError& e) {
    EXPECT_NE(std::string(e.what()).find("flat.png"), std::string::npos) << e.what();
  }
}

TEST(Scene, ShippedScenesParseAndBadFieldsAreNamed) {
  for (const char* f : {"blinn_phong.json", "ggx.json"}) {
    const NmScene s = load_nm_scene(std::string(BL_SOURCE_DIR) + "/scenes/normalmap/" + f);
    EXPECT_TRUE(std::filesystem::exists(s.texture)) << s.texture;
  }
  auto error_of = [](const std::string& text) {
    try {
      parse_nm_scene(text, "bad.json");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string base = R"("texture": "t.png", "material": {"model": "blinn_phong"})";
  EXPECT_NE(error_of("{" + base + ", \"colour\": 1}").find("'colour'"), std::string::npos);
  EXPECT_NE(error_of(R"({"texture": "t.png", "material": {"model": "phong"}})").find("material.model"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"texture": "t.png", "material": {"model": "ggx", "exponent": 8}})")
                .find("material.exponent"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"material": {"model": "ggx"}})").find("'texture'"), std::string::npos);
  EXPECT_NE(error_of("{" + base + ", \"light\": {\"direction\": [0, 0, -1]}}").find("light.direction"),
            std::string::npos);
  EXPECT_NE(error_of("{" + base + ", \"msaa\": [0]}").find("bad.json"), std::string::npos);
}
