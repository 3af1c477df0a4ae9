// A linear-light RGB float image. Row-major, row 0 = TOP, 3 interleaved channels per pixel.
// Pixel (x, y) has its centre at (x + 0.5, y + 0.5) with y growing downward: the convention of
// runtime/camera and of bl::gl::Context::render (whose row 0 is also the top).
#pragma once

#include <cstddef>
#include <vector>

namespace bl {

struct Image {
  static constexpr int kChannels = 3;

  int width = 0;
  int height = 0;
  std::vector<float> pixels;  // width * height * 3, linear RGB

  Image() = default;
  Image(int w, int h, float fill = 0.0f) : width(w), height(h), pixels(size_t(w) * h * kChannels, fill) {}

  size_t index(int x, int y, int c = 0) const { return (size_t(y) * width + x) * kChannels + c; }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
};

// From bl::gl::Context::render's RGBA32F buffer (same row order); alpha is dropped.
Image image_from_rgba(const std::vector<float>& rgba, int width, int height);

}  // namespace bl
