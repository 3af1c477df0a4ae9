// A mip pyramid of an N-channel float image, and the sampling rules of OpenGL's
// GL_LINEAR_MIPMAP_LINEAR with GL_REPEAT, so the C++ evaluator, the emitted C++ and a GLSL
// textureLod() over the same uploaded levels compute the same filtered value (up to the GPU's
// sub-texel weight precision).
//
// Level 0 is the image; level k+1 averages 2x2 texels of level k (a box filter, the "mean of
// values" of the clamped-domain paper's eq. 21). Sides must be powers of two, so every texel of a
// level covers exactly 4^k texels of level 0.
#pragma once

#include <algorithm>
#include <cmath>
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
  // (Inline: emitted C++ shaders sample through this header alone.)
  float bilinear(int k, float u, float v, int c) const {
    const Level& L = levels_[k];
    // Reduced to [0, 1) first so a large |u| cannot overflow the texel index; then GL's rule: texel
    // space minus half a texel, weights from the fractional part.
    const float s = (u - std::floor(u)) * float(L.width) - 0.5f;
    const float t = (v - std::floor(v)) * float(L.height) - 0.5f;
    const float fs = std::floor(s), ft = std::floor(t);
    const float a = s - fs, b = t - ft;
    const int x0 = wrap(int(fs), L.width), y0 = wrap(int(ft), L.height);
    const int x1 = wrap(x0 + 1, L.width), y1 = wrap(y0 + 1, L.height);
    const float top = L.at(x0, y0, c) + a * (L.at(x1, y0, c) - L.at(x0, y0, c));
    const float bottom = L.at(x0, y1, c) + a * (L.at(x1, y1, c) - L.at(x0, y1, c));
    return top + b * (bottom - top);
  }
  // Trilinear: lod clamped to [0, levels - 1] (NaN: 0), linear between floor(lod) and the next level.
  float trilinear(float u, float v, float lod, int c) const {
    const float top = float(levels() - 1);
    if (!(lod > 0.0f)) return bilinear(0, u, v, c);
    if (lod >= top) return bilinear(levels() - 1, u, v, c);
    const int k = int(lod);
    const float f = lod - float(k);
    const float a = bilinear(k, u, v, c);
    return a + f * (bilinear(k + 1, u, v, c) - a);
  }

 private:
  static int wrap(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
  }
  std::vector<Level> levels_;
};

// The level whose filter matches a Gaussian footprint of sd s (in level-0 texels). Reading level L
// bilinearly filters with a box of 2^L texels (the pyramid) convolved with a tent of half-width 2^L
// (the interpolation): variance 4^L / 12 + 4^L / 6 = 4^L / 4. The ground truth is the footprint
// over the bilinearly interpolated level 0, variance s^2 + 1/6. Equal variances:
// lod = log2(4 s^2 + 2/3) / 2 (negative below about half a texel: trilinear clamps it to 0).
inline float lod_for_sd(float s) {
  return 0.5f * std::log2(4.0f * s * s + 0.666666667f);
}

}  // namespace bl::texture
