#include "image/image.hpp"

#include <stdexcept>
#include <string>

namespace bl {

Image image_from_rgba(const std::vector<float>& rgba, int width, int height) {
  if (width < 0 || height < 0 || rgba.size() != size_t(width) * height * 4) {
    throw std::invalid_argument("image_from_rgba: " + std::to_string(rgba.size()) + " floats is not " +
                                std::to_string(width) + "x" + std::to_string(height) + " RGBA");
  }
  Image img(width, height);
  for (size_t p = 0; p < size_t(width) * height; ++p) {
    for (int c = 0; c < 3; ++c) img.pixels[3 * p + c] = rgba[4 * p + c];
  }
  return img;
}

}  // namespace bl
