// Structural similarity (Wang, Bovik, Sheikh, Simoncelli 2004, "Image quality assessment: from
// error visibility to structural similarity"), as in their reference implementation: an 11x11
// Gaussian window (sd 1.5, normalized), K1 = 0.01, K2 = 0.03, dynamic range L = 1, computed where
// the window lies inside the image ("valid"), and averaged over those positions:
//   SSIM(x, y) = (2 mu_x mu_y + C1) (2 s_xy + C2) / ((mu_x^2 + mu_y^2 + C1) (s_x^2 + s_y^2 + C2)),
//   C1 = (K1 L)^2, C2 = (K2 L)^2, with the moments weighted by the window.
// On images: the display-space luma Y' = 0.2126 R' + 0.7152 G' + 0.0722 B' of to_display(),
// the space every other error here is measured in.
#pragma once

#include <vector>

#include "image/image.hpp"

namespace bl {

// Mean SSIM of two single-channel images (row-major, values nominally in [0, 1]). Throws
// std::invalid_argument for different sizes or a side shorter than the 11-pixel window.
// `map`, when given, receives the per-position SSIM ((w - 10) x (h - 10), row-major).
double ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
            std::vector<double>* map = nullptr);

// Display-space luma of an image (to_display per channel, then Rec. 709 weights).
std::vector<double> display_luma(const Image& img);

// ssim(display_luma(a), display_luma(b)).
double ssim_display(const Image& a, const Image& b);

}  // namespace bl
