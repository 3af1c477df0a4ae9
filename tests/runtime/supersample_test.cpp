// Supersampling as a program (compiler/supersample.hpp): the program is the average of the plain
// program at the shifted inputs (computed here by moving the inputs, not by the transformation); the
// offsets are the normal quantiles of a stratified pattern (checked through erfc); bad input is named.
#include "compiler/supersample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "compiler/evaluator.hpp"
#include "compiler/lower.hpp"
#include "rules/rule.hpp"
#include "shaders/shader.hpp"
#include "tests/runtime/random_pixels.hpp"

namespace bl {
namespace {

std::vector<std::vector<float>> run(const compiler::Program& p, const compiler::Batch& b) {
  std::vector<std::vector<float>> out(p.outputs.size(), std::vector<float>(b.count));
  std::vector<float*> ptr;
  for (auto& o : out) ptr.push_back(o.data());
  compiler::Evaluator(p).run(b, ptr);
  return out;
}

compiler::Program plain_of(const char* shader) {
  const ir::Graph g = shaders::trace(shaders::find_shader(shader), {});
  return compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("none")));
}

// Every suite shader: the supersampled program's outputs are the mean of the plain program's at
// (m + gx ox + gy oy) for each offset, to float rounding.
TEST(Supersample, IsTheMeanOfThePlainProgramAtTheShiftedInputs) {
  for (const char* shader : {"checkerboard", "bricks", "zigzag", "fire"}) {
    const compiler::Program plain = plain_of(shader);
    const std::vector<std::array<float, 2>> offs = {{0.3f, -0.2f}, {-0.45f, 0.1f}, {0.05f, 0.6f}};
    const compiler::Program ss = compiler::supersample(plain, offs);
    const testing::RandomPixels px(plain, 300, 11, 6.0f, 0.2f);
    const auto got = run(ss, px.batch());
    std::vector<std::vector<double>> want(plain.outputs.size(), std::vector<double>(px.n, 0.0));
    for (const auto& [ox, oy] : offs) {
      testing::RandomPixels moved = px;
      for (std::size_t j = 0; j < moved.mean.size(); ++j)
        for (int i = 0; i < px.n; ++i) moved.mean[j][i] += px.gx[j][i] * ox + px.gy[j][i] * oy;
      const auto one = run(plain, moved.batch());
      for (std::size_t o = 0; o < one.size(); ++o)
        for (int i = 0; i < px.n; ++i) want[o][i] += one[o][i] / offs.size();
    }
    for (std::size_t o = 0; o < want.size(); ++o)
      for (int i = 0; i < px.n; ++i)
        EXPECT_NEAR(got[o][i], want[o][i], 2e-5) << shader << " output " << o << " pixel " << i;
  }
}

TEST(Supersample, OneOffsetAtTheCentreIsThePlainProgram) {
  const compiler::Program plain = plain_of("bricks");
  const compiler::Program ss = compiler::supersample(plain, compiler::supersample_offsets(1, 0.5));
  const testing::RandomPixels px(plain, 200, 3, 6.0f, 0.2f);
  const auto a = run(plain, px.batch()), b = run(ss, px.batch());
  for (std::size_t o = 0; o < a.size(); ++o)
    for (int i = 0; i < px.n; ++i) EXPECT_EQ(a[o][i], b[o][i]);
}

// x_i = sigma Phi^-1((i + 1/2) / n); for n a power of two the y's are the same set (the radical
// inverse of 0..n-1 is a permutation of k / n).
TEST(Supersample, OffsetsAreStratifiedNormalQuantiles) {
  for (int n : {1, 2, 4, 8, 16, 32}) {
    const double sigma = 0.5;
    const auto offs = compiler::supersample_offsets(n, sigma);
    ASSERT_EQ(offs.size(), static_cast<std::size_t>(n));
    std::vector<float> xs, ys;
    for (int i = 0; i < n; ++i) {
      const double p = 0.5 * std::erfc(-offs[i][0] / sigma / std::sqrt(2.0));
      EXPECT_NEAR(p, (i + 0.5) / n, 1e-6) << "n " << n << " point " << i;
      xs.push_back(offs[i][0]), ys.push_back(offs[i][1]);
    }
    std::sort(ys.begin(), ys.end());
    for (int i = 0; i < n; ++i) EXPECT_FLOAT_EQ(xs[i], ys[i]) << "n " << n;
  }
}

TEST(Supersample, BadInputIsNamed) {
  const compiler::Program plain = plain_of("checkerboard");
  EXPECT_THROW(compiler::supersample(plain, {}), std::invalid_argument);
  const ir::Graph g = shaders::trace(shaders::find_shader("checkerboard"), {});
  const compiler::Program smoothed =
      compiler::lower(g, compiler::uniform_schedule(g, rules::parse_rule("gaussian")));
  try {
    compiler::supersample(smoothed, compiler::supersample_offsets(4, 0.5));
    FAIL() << "a smoothed program was supersampled";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not plain"), std::string::npos) << e.what();
  }
  EXPECT_THROW(compiler::supersample_offsets(0, 0.5), std::invalid_argument);
  EXPECT_THROW(compiler::supersample_offsets(4, 0.0), std::invalid_argument);
  EXPECT_THROW(compiler::supersample_offsets(4, -1.0), std::invalid_argument);
  EXPECT_THROW(compiler::supersample_offsets(4, NAN), std::invalid_argument);
}

}  // namespace
}  // namespace bl
