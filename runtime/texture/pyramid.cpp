#include "texture/pyramid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace bl::texture {
namespace {

bool power_of_two(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

Level halve(const Level& a) {
  Level b;
  b.width = std::max(1, a.width / 2);
  b.height = std::max(1, a.height / 2);
  b.channels = a.channels;
  b.texels.assign(std::size_t(b.width) * b.height * b.channels, 0.0f);
  // A side already at 1 is not halved: its texel is averaged with itself.
  const int sx = a.width > 1 ? 2 : 1, sy = a.height > 1 ? 2 : 1;
  const float w = 1.0f / float(sx * sy);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      for (int c = 0; c < b.channels; ++c) {
        double s = 0;  // double: the 4 partial sums round once
        for (int j = 0; j < sy; ++j)
          for (int i = 0; i < sx; ++i) s += a.at(sx * x + i, sy * y + j, c);
        b.texels[(std::size_t(y) * b.width + x) * b.channels + c] = float(s) * w;
      }
  return b;
}

int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

}  // namespace

Pyramid::Pyramid(Level base) {
  if (base.channels < 1) throw std::invalid_argument("texture pyramid: no channels");
  if (!power_of_two(base.width) || !power_of_two(base.height))
    throw std::invalid_argument("texture pyramid: size " + std::to_string(base.width) + "x" +
                                std::to_string(base.height) + " is not a power of two on each side");
  if (base.texels.size() != std::size_t(base.width) * base.height * base.channels)
    throw std::invalid_argument("texture pyramid: texel count does not match the size");
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(halve(levels_.back()));
}

float Pyramid::bilinear(int k, float u, float v, int c) const {
  const Level& L = levels_[k];
  // GL: texel space coordinate minus half a texel, weights from its fractional part.
  // The coordinate is reduced to [0, 1) first so a large |u| cannot overflow the texel index.
  const float s = (u - std::floor(u)) * float(L.width) - 0.5f,
              t = (v - std::floor(v)) * float(L.height) - 0.5f;
  const float fs = std::floor(s), ft = std::floor(t);
  const float a = s - fs, b = t - ft;
  const int x0 = wrap(int(fs), L.width), y0 = wrap(int(ft), L.height);
  const int x1 = wrap(x0 + 1, L.width), y1 = wrap(y0 + 1, L.height);
  const float top = L.at(x0, y0, c) + a * (L.at(x1, y0, c) - L.at(x0, y0, c));
  const float bottom = L.at(x0, y1, c) + a * (L.at(x1, y1, c) - L.at(x0, y1, c));
  return top + b * (bottom - top);
}

float Pyramid::trilinear(float u, float v, float lod, int c) const {
  const float top = float(levels() - 1);
  if (!(lod > 0.0f)) return bilinear(0, u, v, c);  // also NaN: the finest level
  if (lod >= top) return bilinear(levels() - 1, u, v, c);
  const int k = int(lod);
  const float f = lod - float(k);
  const float a = bilinear(k, u, v, c);
  return a + f * (bilinear(k + 1, u, v, c) - a);
}

float footprint_lod(float su, float sv, int width, int height) {
  const float s = std::max(su * float(width), sv * float(height));
  return std::log2(std::max(s * 3.46410162f, 1e-30f));
}

}  // namespace bl::texture
