#include "image/report.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "image/colormap.hpp"
#include "image/display.hpp"
#include "image/image_io.hpp"
#include "image/metrics.hpp"

namespace bl {
namespace {

constexpr int kGap = 4;
constexpr int kLabelBand = 22;
constexpr float kBackground = 0.02f;  // linear; dark gray on screen

void paste(Image& dst, const Image& src, int x0, int y0) {
  for (int y = 0; y < src.height; ++y) {
    std::copy_n(&src.pixels[src.index(0, y)], size_t(src.width) * 3, &dst.pixels[dst.index(x0, y0 + y)]);
  }
}

void set_display_color(Image& img, int x, int y, const std::array<float, 3>& display) {
  for (int c = 0; c < 3; ++c) img.at(x, y, c) = from_display(display[c]);
}

}  // namespace

bool draw_text(Image& img, int x, int y, const std::string& text, int size_px) {
  if (text.empty() || img.width == 0 || img.height == 0) return true;
  OIIO::ImageSpec spec(img.width, img.height, Image::kChannels, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf buf(spec, img.pixels.data());  // wraps the pixels: drawing writes through
  const float white[3] = {1.0f, 1.0f, 1.0f};
  for (const char* font : {"DejaVuSans", "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"}) {
    if (OIIO::ImageBufAlgo::render_text(buf, x, y, text, size_px, font, white)) return true;
    (void)buf.geterror();  // clear, then try the next font name
  }
  return false;
}

double write_error_heatmap(const std::string& path, const Image& a, const Image& b) {
  require_same_size(a, b, "write_error_heatmap");
  const std::vector<float> err = error_map_display(a, b);
  const double max_error = err.empty() ? 0.0 : *std::max_element(err.begin(), err.end());
  const int bar = std::max(6, a.height / 16);
  Image out(a.width, a.height + 2 + bar + kLabelBand, kBackground);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const float t = max_error > 0 ? float(err[size_t(y) * a.width + x] / max_error) : 0.0f;
      set_display_color(out, x, y, viridis(t));
    }
  }
  for (int x = 0; x < a.width; ++x) {
    const auto color = viridis(a.width > 1 ? float(x) / (a.width - 1) : 0.0f);
    for (int y = a.height + 2; y < a.height + 2 + bar; ++y) set_display_color(out, x, y, color);
  }
  char scale[96];
  std::snprintf(scale, sizeof(scale), "max %.4g", max_error);
  const int baseline = a.height + 2 + bar + kLabelBand - 6;
  if (draw_text(out, 2, baseline, "0")) draw_text(out, std::max(12, a.width / 2), baseline, scale);
  char description[160];
  std::snprintf(description, sizeof(description),
                "bandlimit error heatmap: per-pixel display-space L2 over RGB, viridis from 0 to %.6g",
                max_error);
  if (path.size() >= 4 && path.substr(path.size() - 4) == ".png") {
    write_png(path, out, description);
  } else {
    write_image(path, out);
  }
  return max_error;
}

void write_side_by_side(const std::string& path, const std::vector<Image>& images,
                        const std::vector<std::string>& labels) {
  if (images.empty()) throw std::invalid_argument("write_side_by_side('" + path + "'): no images");
  if (!labels.empty() && labels.size() != images.size()) {
    throw std::invalid_argument("write_side_by_side('" + path + "'): " + std::to_string(labels.size()) +
                                " labels for " + std::to_string(images.size()) + " images");
  }
  int width = kGap * int(images.size() - 1), height = 0;
  for (const Image& img : images) {
    width += img.width;
    height = std::max(height, img.height);
  }
  const int band = labels.empty() ? 0 : kLabelBand;
  Image out(width, height + band, kBackground);
  int x = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    paste(out, images[i], x, 0);
    if (!labels.empty()) draw_text(out, x + 2, height + band - 6, labels[i]);
    x += images[i].width + kGap;
  }
  write_image(path, out);
}

}  // namespace bl
