// Perceptual colormap for error heatmaps.
#pragma once

#include <array>

namespace bl {

// matplotlib's viridis (CC0; van der Walt, Smith, Firing) sampled at t = k/10 and interpolated
// linearly; t is clamped to [0, 1]. Returns DISPLAY-space (sRGB-encoded) RGB.
std::array<float, 3> viridis(float t);

}  // namespace bl
