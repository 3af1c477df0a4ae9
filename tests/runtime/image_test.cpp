// bl::Image I/O, display space and metrics against values computed by hand.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "image/colormap.hpp"
#include "image/display.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"
#include "image/pixel_check.hpp"
#include "image/report.hpp"

namespace fs = std::filesystem;

namespace {

class RuntimeImage : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("bl_image_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  // Everything in the directory whose name contains ".tmp": leftovers of a write.
  int temp_files() const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir_))
      n += e.path().filename().string().find(".tmp") != std::string::npos;
    return n;
  }
  fs::path dir_;
};

bl::Image ramp(int w, int h) {
  bl::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      img.at(x, y, 0) = 0.013f * x - 0.1f;  // some negatives and values above 1
      img.at(x, y, 1) = std::sin(0.7f * x + 1.3f * y) * 1.5f;
      img.at(x, y, 2) = 1e-4f * (x + 1) * (y + 1);
    }
  return img;
}

// The sRGB transfer function at a few points, computed by hand from IEC 61966-2-1.
TEST(RuntimeImageDisplay, SrgbByHand) {
  EXPECT_NEAR(bl::to_display(0.5f), 0.7353569830524495, 1e-6);  // 1.055 * 0.5^(1/2.4) - 0.055
  EXPECT_NEAR(bl::to_display(0.002f), 0.02584, 1e-6);           // 12.92 * 0.002
  EXPECT_NEAR(bl::to_display(0.0031308f), 0.04045, 1e-5);       // the two pieces meet
  EXPECT_EQ(bl::to_display(-3.0f), 0.0f);
  EXPECT_EQ(bl::to_display(7.0f), 1.0f);
  EXPECT_NEAR(bl::to_display(1.0f), 1.0, 1e-6);
  for (float v : {0.0f, 0.001f, 0.01f, 0.2f, 0.5f, 0.9f, 1.0f})
    EXPECT_NEAR(bl::from_display(bl::to_display(v)), v, 1e-6);
}

TEST_F(RuntimeImage, ExrRoundTripsExactly) {
  const bl::Image img = ramp(37, 19);
  bl::write_exr(file("a.exr"), img);
  const bl::Image back = bl::read_image(file("a.exr"));
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 19);
  EXPECT_EQ(back.pixels, img.pixels);  // bit-exact, including negatives and values > 1
  EXPECT_EQ(temp_files(), 0);
}

TEST_F(RuntimeImage, PngRoundTripsWithinOneLevelInDisplaySpace) {
  bl::Image img = ramp(23, 11);
  img.at(0, 0, 0) = 0.5f;  // sRGB byte 188 = round(0.73536 * 255)
  bl::write_png(file("a.png"), img);
  const bl::Image back = bl::read_image(file("a.png"));
  ASSERT_EQ(back.width, 23);
  ASSERT_EQ(back.height, 11);
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    ASSERT_LE(std::abs(bl::to_display(back.pixels[i]) - bl::to_display(img.pixels[i])), 0.5f / 255 + 1e-6f)
        << i;
  }
  auto in = OIIO::ImageInput::open(file("a.png"));
  ASSERT_TRUE(in);
  unsigned char px[3 * 23 * 11];
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px));
  EXPECT_EQ(px[0], 188);
}

TEST_F(RuntimeImage, RowZeroIsTop) {
  bl::Image img(2, 3, 0.0f);
  img.at(1, 0, 1) = 1.0f;  // top-right pixel green
  bl::write_png(file("o.png"), img);
  auto in = OIIO::ImageInput::open(file("o.png"));
  unsigned char px[2 * 3 * 3];
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px));
  EXPECT_EQ(px[3 + 1], 255);  // file scanline 0 is the top in every image format
  EXPECT_EQ(px[3 * 2 * 2 + 3 + 1], 0);
}

TEST(RuntimeImageMetrics, RmsAndPsnrByHand) {
  bl::Image a(2, 1, 0.0f), b(2, 1, 0.0f);
  b.at(0, 0, 0) = 1.0f;
  b.at(1, 0, 2) = 4.0f;  // not clamped: 1.055 * 4^(1/2.4) - 0.055 = 1.8247962952761159 (Python)
  // Squared display differences: 1, 0, 0, 0, 0, 1.8248^2 -> sqrt((1 + 1.8248^2) / 6).
  EXPECT_NEAR(bl::rms_display(a, b), 0.8494980399480465, 1e-6);
  EXPECT_NEAR(bl::psnr_display(a, b), 1.4167523768811647, 1e-5);
  b.at(1, 0, 2) = NAN;  // a NaN channel counts as the whole display range
  EXPECT_NEAR(bl::rms_display(a, b), std::sqrt(2.0 / 6.0), 1e-7);
  b.at(0, 0, 0) = 0.5f;
  b.at(1, 0, 2) = 0.0f;
  EXPECT_NEAR(bl::rms_display(a, b), 0.7353569830524495 / std::sqrt(6.0), 1e-7);
  EXPECT_TRUE(std::isinf(bl::psnr_display(a, a)));
  const auto err = bl::error_map_display(a, b);
  EXPECT_NEAR(err[0], 0.7353569830524495, 1e-6);
  EXPECT_EQ(err[1], 0.0f);
}

TEST(RuntimeImageMetrics, SizeMismatchNamesBothSizes) {
  bl::Image a(2, 1), b(3, 1);
  try {
    bl::rms_display(a, b);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2x1 vs 3x1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(bl::psnr_display(a, b), std::invalid_argument);
}

TEST_F(RuntimeImage, ErrorsNameTheFile) {
  try {
    bl::read_image(file("missing.exr"));
    FAIL();
  } catch (const bl::ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.exr"), std::string::npos) << e.what();
  }
  // A one-channel file written behind the library's back.
  {
    auto out = OIIO::ImageOutput::create(file("gray.exr"));
    OIIO::ImageSpec spec(4, 4, 1, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(file("gray.exr"), spec));
    std::vector<float> px(16, 0.5f);
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data()));
    out->close();
  }
  try {
    bl::read_image(file("gray.exr"));
    FAIL();
  } catch (const bl::ImageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gray.exr"), std::string::npos) << what;
    EXPECT_NE(what.find("1 channels"), std::string::npos) << what;
  }
  std::ofstream(file("junk.png")) << "not a png";
  EXPECT_THROW(bl::read_image(file("junk.png")), bl::ImageError);
}

TEST_F(RuntimeImage, FailedWritesLeaveNothing) {
  const bl::Image img = ramp(4, 4);
  EXPECT_THROW(bl::write_exr(file("no/such/dir/a.exr"), img), bl::ImageError);
  EXPECT_THROW(bl::write_png(file("a.exr"), img), bl::ImageError);  // wrong extension
  EXPECT_THROW(bl::write_exr(file("empty.exr"), bl::Image()), bl::ImageError);
  EXPECT_FALSE(fs::exists(file("a.exr")));
  EXPECT_FALSE(fs::exists(file("empty.exr")));
  EXPECT_EQ(temp_files(), 0);
}

TEST_F(RuntimeImage, HeatmapScaleAndColors) {
  bl::Image a(8, 8, 0.0f), b(8, 8, 0.0f);
  b.at(5, 2, 0) = 1.0f;
  b.at(5, 2, 1) = 1.0f;  // display L2 error sqrt(2) there, 0 elsewhere
  b.at(1, 6, 2) = 0.5f;  // 0.7353... there
  const double max_error = bl::write_error_heatmap(file("h.png"), a, b);
  EXPECT_NEAR(max_error, std::sqrt(2.0), 1e-6);
  auto in = OIIO::ImageInput::open(file("h.png"));
  ASSERT_TRUE(in);
  const auto spec = in->spec();
  EXPECT_EQ(spec.width, 8);
  EXPECT_GT(spec.height, 8);  // map plus colour bar
  EXPECT_NE(spec.get_string_attribute("ImageDescription").find("1.41421"), std::string::npos);
  std::vector<unsigned char> px(size_t(spec.width) * spec.height * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  auto pixel = [&](int x, int y, int c) { return px[(size_t(y) * 8 + x) * 3 + c] / 255.0; };
  // matplotlib viridis endpoints: (0.267004, 0.004874, 0.329415) and (0.993248, 0.906157, 0.143936).
  EXPECT_NEAR(pixel(0, 0, 0), 0.267004, 1.0 / 255);
  EXPECT_NEAR(pixel(0, 0, 2), 0.329415, 1.0 / 255);
  EXPECT_NEAR(pixel(5, 2, 0), 0.993248, 1.0 / 255);
  EXPECT_NEAR(pixel(5, 2, 1), 0.906157, 1.0 / 255);
  // 0.7353 / 1.4142 = 0.52: between viridis(0.5) = (0.127568, 0.566949, 0.550556) and viridis(0.6).
  EXPECT_GT(pixel(1, 6, 1), 0.566949 - 1.0 / 255);
  EXPECT_LT(pixel(1, 6, 1), 0.658636);
}

TEST_F(RuntimeImage, SideBySidePastesLeftToRight) {
  bl::Image a(3, 2, 0.25f), b(2, 4, 1.0f);
  bl::write_side_by_side(file("s.exr"), {a, b});
  const bl::Image s = bl::read_image(file("s.exr"));
  ASSERT_EQ(s.width, 3 + 4 + 2);  // 4-pixel gap
  ASSERT_EQ(s.height, 4);
  EXPECT_EQ(s.at(2, 1, 0), 0.25f);
  EXPECT_EQ(s.at(7, 3, 2), 1.0f);
  EXPECT_LT(s.at(4, 0, 0), 0.1f);  // the gap is background
  EXPECT_LT(s.at(0, 3, 0), 0.1f);  // under the shorter image too
  bl::write_side_by_side(file("l.png"), {a, b}, {"ground truth", "ours"});
  EXPECT_EQ(bl::read_image(file("l.png")).height, 4 + 22);
  EXPECT_THROW(bl::write_side_by_side(file("x.png"), {a, b}, {"one"}), std::invalid_argument);
}

}  // namespace

// The error curve: the display curve on [0, 1], continued (odd-symmetric, same power law) outside.
TEST(RuntimeImageMetrics, UnclampedDisplayCurve) {
  for (float v = 0; v <= 1.0f; v += 1.0f / 64) EXPECT_EQ(bl::to_display_unclamped(v), bl::to_display(v)) << v;
  EXPECT_NEAR(bl::to_display_unclamped(-0.5f), -0.7353569830524495, 1e-6);
  EXPECT_NEAR(bl::to_display_unclamped(4.0f), 1.8247962952761159, 1e-6);
  EXPECT_NEAR(bl::to_display_unclamped(-0.002f), -0.02584, 1e-6);
  EXPECT_TRUE(std::isnan(bl::to_display_unclamped(NAN)));
  EXPECT_EQ(bl::display_error(NAN, 0.3f), 1.0);
  EXPECT_EQ(bl::display_error(0.3f, -INFINITY), 1.0);
  // The clamp hid this: 10.95 against 0.95 was an error of 0.023 in display space.
  EXPECT_NEAR(bl::display_error(10.95f, 0.95f),
              (1.055 * std::pow(10.95, 1 / 2.4) - 0.055) - (1.055 * std::pow(0.95, 1 / 2.4) - 0.055), 1e-5);
}

// NaN/inf and out-of-range pixels are counted, once per pixel, nonfinite first.
TEST(RuntimeImageMetrics, CountsNonFiniteAndOutOfRangePixels) {
  bl::Image img(4, 3, 0.5f);
  img.at(0, 0, 1) = NAN;        // nonfinite
  img.at(1, 0, 0) = INFINITY;   // nonfinite
  img.at(2, 0, 2) = -INFINITY;  // nonfinite
  img.at(2, 0, 0) = 7.0f;       //   (the same pixel: still one nonfinite pixel, not out of range)
  img.at(3, 0, 0) = -0.2f;      // out of range
  img.at(0, 1, 1) = 1.5f;       // out of range for [0, 1]; inside a truth range reaching 1.6 in G
  img.at(1, 1, 2) = 1.0001f;    // out of range
  img.at(2, 1, 0) = 0.0f;       // the ends are inside
  img.at(2, 1, 2) = 1.0f;
  img.at(3, 2, 0) = 1.5f;  // out of range in R (the truth reaches 1.6 in G only)
  bl::PixelCounts n = bl::check_pixels(img);
  EXPECT_EQ(n.nonfinite, 3u);
  EXPECT_EQ(n.out_of_range, 4u);
  bl::Image truth(4, 3, 0.2f);
  truth.at(1, 2, 1) = 1.6f;
  truth.at(0, 2, 0) = NAN;  // ignored by the range
  const bl::ValueRange r = bl::ValueRange::of({truth});
  EXPECT_EQ(r.lo[0], 0.0f);
  EXPECT_EQ(r.hi[0], 1.0f);
  EXPECT_EQ(r.hi[1], 1.6f);
  n = bl::check_pixels(img, r);
  EXPECT_EQ(n.nonfinite, 3u);
  EXPECT_EQ(n.out_of_range, 3u);
  // Float rounding at a bound is inside (a plain circles pixel, 0.1f + 0.8f = 0.90000004, against
  // the declared [0.1, 0.9] stored as 0.89999998f); an overshoot of 1e-4 is not.
  bl::ValueRange circles;
  circles.lo = {0.1f, 0.1f, 0.1f};
  circles.hi = {0.9f, 0.9f, 0.9f};
  const float top[3] = {0.1f + 0.8f, 0.1f + 0.8f, 0.1f + 0.8f};
  EXPECT_GT(top[0], 0.9f);
  EXPECT_EQ(bl::check_pixel(top, circles).out_of_range, 0u);
  const float over[3] = {0.9f + 1e-4f, 0.5f, 0.5f}, under[3] = {0.5f, 0.1f - 1e-4f, 0.5f};
  EXPECT_EQ(bl::check_pixel(over, circles).out_of_range, 1u);
  EXPECT_EQ(bl::check_pixel(under, circles).out_of_range, 1u);
}
