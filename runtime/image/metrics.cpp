#include "image/metrics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "image/display.hpp"

namespace bl {

void require_same_size(const Image& a, const Image& b, const char* what) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument(std::string(what) + ": image sizes differ: " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                                std::to_string(b.height));
  }
}

double rms_display(const Image& a, const Image& b) {
  require_same_size(a, b, "rms_display");
  if (a.pixels.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = display_error(a.pixels[i], b.pixels[i]);
    sum += d * d;
  }
  return std::sqrt(sum / a.pixels.size());
}

double psnr_display(const Image& a, const Image& b) {
  require_same_size(a, b, "psnr_display");
  const double rms = rms_display(a, b);
  return rms == 0.0 ? std::numeric_limits<double>::infinity() : -20.0 * std::log10(rms);
}

std::vector<float> error_map_display(const Image& a, const Image& b) {
  require_same_size(a, b, "error_map_display");
  std::vector<float> err(size_t(a.width) * a.height);
  for (size_t p = 0; p < err.size(); ++p) {
    double sum = 0.0;
    for (int c = 0; c < Image::kChannels; ++c) {
      const double d = display_error(a.pixels[3 * p + c], b.pixels[3 * p + c]);
      sum += d * d;
    }
    err[p] = float(std::sqrt(sum));
  }
  return err;
}

}  // namespace bl
