// Display space: what a viewer sees, where errors are measured (DESIGN.md: RMS in display space).
// to_display(v) = srgb_encode(clamp(v, 0, 1)) with the sRGB transfer function (IEC 61966-2-1):
//   12.92 v                    for v <= 0.0031308
//   1.055 v^(1/2.4) - 0.055    otherwise.
// from_display is its inverse on [0, 1] (used to decode 8/16-bit files, which store display values).
#pragma once

namespace bl {

float to_display(float linear);
float from_display(float display);

// The same curve without the clamp, for errors (metrics.hpp): odd-symmetric beyond 0 and continued
// above 1 ("extended sRGB", as scRGB / Apple's extended sRGB do), so it equals to_display on [0, 1]
// and a value outside [0, 1] keeps its distance instead of vanishing into the clamp. NaN and
// infinities pass through (the metrics count them, image/pixel_check.hpp).
float to_display_unclamped(float linear);

// |error| of one channel as the metrics count it: to_display_unclamped(a) - to_display_unclamped(b),
// and 1 (the whole display range) where either value is NaN or infinite.
double display_error(float a, float b);

}  // namespace bl
