// Honest pixel checks: the display mapping (display.hpp) clamps to [0, 1] and sends NaN to 0, so a
// broken value can vanish from an image. These count, per image, the pixels a metric must not hide:
// a channel that is NaN or infinite, and a (finite) channel outside the valid range, per channel
// (render/value_range.hpp builds a scene's: the shader's declared range, or [0, 1] widened to the
// observed values, so a shader whose true values exceed 1, a highlight, is not flagged for them).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "image/image.hpp"

namespace bl {

struct ValueRange {
  std::array<float, Image::kChannels> lo{0, 0, 0}, hi{1, 1, 1};
  // [0, 1] widened per channel to the finite values of `images`.
  static ValueRange of(const std::vector<Image>& images);
  // Inside up to float rounding: 16 ulps of the bound (at least of 1), so 0.1f + 0.8f = 0.90000004
  // is inside a declared [0.1, 0.9] (stored as 0.89999998f); a real overshoot is far larger.
  bool contains(int channel, float v) const {
    return v >= lo[channel] - slack(lo[channel]) && v <= hi[channel] + slack(hi[channel]);
  }
  static float slack(float bound) {
    const float m = bound < 0 ? -bound : bound;
    return 16 * 1.1920929e-7f * (m > 1 ? m : 1);
  }
};

// A shader's declared bounds per channel (render/value_range.hpp: interval analysis, with the
// background), a non-finite entry where it declares none: they replace `seen` on the sides declared.
struct DeclaredBounds {
  std::array<float, Image::kChannels> lo{NAN, NAN, NAN}, hi{NAN, NAN, NAN};
};
ValueRange bounded(ValueRange seen, const DeclaredBounds& declared);

struct PixelCounts {
  std::size_t nonfinite = 0;     // pixels with a NaN or infinite channel
  std::size_t out_of_range = 0;  // other pixels with a channel outside the range
  PixelCounts& operator+=(const PixelCounts& o) {
    nonfinite += o.nonfinite;
    out_of_range += o.out_of_range;
    return *this;
  }
};

// One pixel's channels (Image::kChannels values).
PixelCounts check_pixel(const float* rgb, const ValueRange& r);
PixelCounts check_pixels(const Image& img, const ValueRange& r = {});

}  // namespace bl
