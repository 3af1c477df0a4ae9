// Reading and writing images through OpenImageIO. Every error names the file. Writers go through
// a temporary file in the same directory and rename it, so a failed write leaves no partial file.
#pragma once

#include <stdexcept>
#include <string>

#include "image/image.hpp"

namespace bl {

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Any format OpenImageIO reads, with 3 (RGB) or 4 (RGBA, alpha dropped) channels; others throw.
// Float/half files (EXR, HDR, float TIFF) are taken as linear. Integer files (PNG, JPEG, 8/16-bit
// TIFF) are taken as display-encoded sRGB and decoded with from_display, so read_image(write_png(x))
// returns linear values again.
Image read_image(const std::string& path);

// 32-bit float RGB OpenEXR (zip, lossless): round-trips exactly. The path must end in .exr.
void write_exr(const std::string& path, const Image& img);

// 8-bit RGB PNG of to_display(img), rounded to nearest. The path must end in .png. A non-empty
// description is stored as the file's ImageDescription.
void write_png(const std::string& path, const Image& img, const std::string& description = "");

// write_exr or write_png by the path's extension.
void write_image(const std::string& path, const Image& img);

}  // namespace bl
