#include "image/display.hpp"

#include <algorithm>
#include <cmath>

namespace bl {

float to_display(float linear) {
  // NaN is treated as 0 so that a broken pixel shows as an error instead of poisoning the RMS.
  const float v = std::isnan(linear) ? 0.0f : std::clamp(linear, 0.0f, 1.0f);
  if (v == 1.0f) return 1.0f;  // pow rounds 1.055 - 0.055 to 0.99999994: keep white exact
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float to_display_unclamped(float linear) {
  if (!std::isfinite(linear)) return linear;
  const float v = std::fabs(linear);
  const float e = v == 1.0f         ? 1.0f
                  : v <= 0.0031308f ? 12.92f * v
                                    : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return std::copysign(e, linear);
}

double display_error(float a, float b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return 1.0;
  return double(to_display_unclamped(a)) - to_display_unclamped(b);
}

float from_display(float display) {
  const float v = std::isnan(display) ? 0.0f : std::clamp(display, 0.0f, 1.0f);
  if (v == 1.0f) return 1.0f;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace bl
