// Error metrics in display space (see display.hpp). All throw std::invalid_argument naming both
// sizes when the images differ in size. Errors are measured on the unclamped display curve
// (display_error): a value outside [0, 1] counts with its distance, a NaN or infinite channel as an
// error of 1; image/pixel_check.hpp counts such pixels so reports can show them beside the RMS.
#pragma once

#include <vector>

#include "image/image.hpp"

namespace bl {

// sqrt(mean over all pixels and channels of display_error(a, b)^2).
double rms_display(const Image& a, const Image& b);

// 20 log10(1 / rms_display): peak value 1. +infinity for identical images.
double psnr_display(const Image& a, const Image& b);

// Per-pixel L2 norm over the three channels of the display-space difference, row 0 = top.
std::vector<float> error_map_display(const Image& a, const Image& b);

void require_same_size(const Image& a, const Image& b, const char* what);

}  // namespace bl
