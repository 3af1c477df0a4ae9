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

}  // namespace bl::texture
