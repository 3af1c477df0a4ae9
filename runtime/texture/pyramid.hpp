// A mip pyramid of an N-channel float image, and the sampling rules of OpenGL's
// GL_LINEAR_MIPMAP_LINEAR with GL_REPEAT, so the C++ evaluator, the emitted C++ and a GLSL
// textureLod() over the same uploaded levels compute the same filtered value (up to the GPU's
// sub-texel weight precision).
//
// Level 0 is the image; level k+1 averages 2x2 texels of level k (a box filter, the "mean of
// values" of the clamped-domain paper's eq. 21). Sides must be powers of two, so every texel of a
// level covers exactly 4^k texels of level 0.
#pragma once

#include <cstddef>
#include <vector>

namespace bl::texture {

struct Level {
  int width = 0, height = 0, channels = 0;
  std::vector<float> texels;  // row-major, row 0 = v in [0, 1/height), interleaved channels

  float at(int x, int y, int c) const { return texels[(std::size_t(y) * width + x) * channels + c]; }
};

class Pyramid {
 public:
  Pyramid() = default;
  // Builds every level down to 1x1. Throws std::invalid_argument when a side is not a power of
  // two or the level is empty or its texel count does not match.
  explicit Pyramid(Level base);

  int levels() const { return static_cast<int>(levels_.size()); }
  int channels() const { return levels_.empty() ? 0 : levels_[0].channels; }
  int width() const { return levels_.empty() ? 0 : levels_[0].width; }
  int height() const { return levels_.empty() ? 0 : levels_[0].height; }
  const Level& level(int k) const { return levels_.at(k); }

  // Bilinear at level k, texture coordinates (u, v) wrapped (GL_REPEAT): texel centres at
  // (i + 0.5) / width.
  float bilinear(int k, float u, float v, int c) const;
  // Trilinear: lod clamped to [0, levels - 1], linear between floor(lod) and the next level.
  float trilinear(float u, float v, float lod, int c) const;

 private:
  std::vector<Level> levels_;
};

// The level whose box texel matches a Gaussian footprint of standard deviation (su, sv) in
// texture coordinates: a box of width w texels has sd w / sqrt(12), so lod = log2(sqrt(12) s) with s
// the larger sd in level-0 texels. Below one texel the lod is negative and trilinear clamps it to 0.
float footprint_lod(float su, float sv, int width, int height);

}  // namespace bl::texture
