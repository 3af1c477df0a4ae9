// Pictures for reports: error heatmaps and labelled side-by-side strips.
#pragma once

#include <string>
#include <vector>

#include "image/image.hpp"

namespace bl {

// Writes the per-pixel display-space error of a against b (L2 over RGB, error_map_display) through
// viridis, scaled so that 0 is the darkest colour and the image's maximum error the brightest.
// Below the map: a colour bar from 0 to that maximum, labelled "0" and "max <value>" when a font is
// available (DejaVu Sans through OpenImageIO); the scale is always in the file's ImageDescription.
// .png or .exr by extension. Returns the maximum error (0 for identical images: all darkest).
double write_error_heatmap(const std::string& path, const Image& a, const Image& b);

// Images left to right with a 4-pixel gap, top-aligned, on a dark background; labels (empty, or
// one per image) are drawn under each image when a font is available. .png or .exr by extension.
void write_side_by_side(const std::string& path, const std::vector<Image>& images,
                        const std::vector<std::string>& labels = {});

// Draws white text with its baseline at (x, y); false (and nothing drawn) when no font renders.
bool draw_text(Image& img, int x, int y, const std::string& text, int size_px = 14);

}  // namespace bl
