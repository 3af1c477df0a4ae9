// Display space: what a viewer sees, where errors are measured (DESIGN.md: RMS in display space).
// to_display(v) = srgb_encode(clamp(v, 0, 1)) with the sRGB transfer function (IEC 61966-2-1):
//   12.92 v                    for v <= 0.0031308
//   1.055 v^(1/2.4) - 0.055    otherwise.
// from_display is its inverse on [0, 1] (used to decode 8/16-bit files, which store display values).
#pragma once

namespace bl {

float to_display(float linear);
float from_display(float display);

}  // namespace bl
