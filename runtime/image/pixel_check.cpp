#include "image/pixel_check.hpp"

#include <algorithm>
#include <cmath>

namespace bl {

ValueRange ValueRange::of(const std::vector<Image>& truths) {
  ValueRange r;
  for (const Image& t : truths)
    for (std::size_t i = 0; i < t.pixels.size(); ++i) {
      const float v = t.pixels[i];
      if (!std::isfinite(v)) continue;
      const int c = static_cast<int>(i % Image::kChannels);
      r.lo[c] = std::min(r.lo[c], v);
      r.hi[c] = std::max(r.hi[c], v);
    }
  return r;
}

ValueRange bounded(ValueRange seen, const DeclaredBounds& declared) {
  for (int c = 0; c < Image::kChannels; ++c) {
    if (std::isfinite(declared.lo[c])) seen.lo[c] = declared.lo[c];
    if (std::isfinite(declared.hi[c])) seen.hi[c] = declared.hi[c];
  }
  return seen;
}

PixelCounts check_pixel(const float* rgb, const ValueRange& r) {
  bool nonfinite = false, outside = false;
  for (int c = 0; c < Image::kChannels; ++c) {
    if (!std::isfinite(rgb[c]))
      nonfinite = true;
    else if (!r.contains(c, rgb[c]))
      outside = true;
  }
  PixelCounts n;
  n.nonfinite = nonfinite;
  n.out_of_range = !nonfinite && outside;
  return n;
}

PixelCounts check_pixels(const Image& img, const ValueRange& r) {
  PixelCounts n;
  for (std::size_t p = 0; p + Image::kChannels <= img.pixels.size(); p += Image::kChannels)
    n += check_pixel(&img.pixels[p], r);
  return n;
}

}  // namespace bl
