#include "image/ssim.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "image/display.hpp"
#include "image/metrics.hpp"

namespace bl {

namespace {

constexpr int kRadius = 5;  // 11 taps
constexpr double kSigma = 1.5;

// "Valid" separable filtering: out is (w - 10) x (h - 10).
std::vector<double> filter_valid(const std::vector<double>& in, int w, int h, const double* k) {
  const int ow = w - 2 * kRadius, oh = h - 2 * kRadius;
  std::vector<double> tmp(std::size_t(ow) * h), out(std::size_t(ow) * oh);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int t = 0; t <= 2 * kRadius; ++t) s += k[t] * in[std::size_t(y) * w + x + t];
      tmp[std::size_t(y) * ow + x] = s;
    }
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int t = 0; t <= 2 * kRadius; ++t) s += k[t] * tmp[std::size_t(y + t) * ow + x];
      out[std::size_t(y) * ow + x] = s;
    }
  return out;
}

}  // namespace

double ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
            std::vector<double>* map) {
  const std::size_t n = std::size_t(width) * height;
  if (x.size() != n || y.size() != n)
    throw std::invalid_argument("ssim: the images must both hold " + std::to_string(width) + "x" +
                                std::to_string(height) + " values");
  if (width < 2 * kRadius + 1 || height < 2 * kRadius + 1)
    throw std::invalid_argument("ssim: images of " + std::to_string(width) + "x" + std::to_string(height) +
                                " are smaller than the 11x11 window");
  double k[2 * kRadius + 1], sum = 0;
  for (int t = -kRadius; t <= kRadius; ++t)
    sum += k[t + kRadius] = std::exp(-0.5 * t * t / (kSigma * kSigma));
  for (double& v : k) v /= sum;
  std::vector<double> xx(n), yy(n), xy(n);
  for (std::size_t i = 0; i < n; ++i) xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
  const auto mx = filter_valid(x, width, height, k), my = filter_valid(y, width, height, k);
  const auto mxx = filter_valid(xx, width, height, k), myy = filter_valid(yy, width, height, k);
  const auto mxy = filter_valid(xy, width, height, k);
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double total = 0;
  if (map) map->resize(mx.size());
  for (std::size_t i = 0; i < mx.size(); ++i) {
    const double sx = mxx[i] - mx[i] * mx[i], sy = myy[i] - my[i] * my[i], sxy = mxy[i] - mx[i] * my[i];
    const double s =
        (2 * mx[i] * my[i] + c1) * (2 * sxy + c2) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (sx + sy + c2));
    total += s;
    if (map) (*map)[i] = s;
  }
  return total / double(mx.size());
}

std::vector<double> display_luma(const Image& img) {
  std::vector<double> out(std::size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      out[std::size_t(y) * img.width + x] = 0.2126 * to_display(img.at(x, y, 0)) +
                                            0.7152 * to_display(img.at(x, y, 1)) +
                                            0.0722 * to_display(img.at(x, y, 2));
  return out;
}

double ssim_display(const Image& a, const Image& b) {
  require_same_size(a, b, "ssim_display");
  return ssim(display_luma(a), display_luma(b), a.width, a.height);
}

}  // namespace bl
