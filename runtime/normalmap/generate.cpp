#include "normalmap/generate.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace bl::normalmap {

namespace {

struct Rng {
  std::uint64_t s;
  double next() {  // splitmix64 -> [0, 1)
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53;
  }
};

// Periodic offset from a to b on a ring of length n, in (-n/2, n/2].
double wrap(double d, double n) {
  d = std::fmod(d, n);
  if (d > 0.5 * n) d -= n;
  if (d <= -0.5 * n) d += n;
  return d;
}

// Adds a groove of depth `depth` and half-width `w` along the segment (x0,y0)-(x1,y1), periodic.
void scratch(std::vector<double>& h, int n, double x0, double y0, double x1, double y1, double depth,
             double w) {
  const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
  const int r = int(std::ceil(3 * w)) + 1;
  const int xmin = int(std::floor(std::min(x0, x1))) - r, xmax = int(std::ceil(std::max(x0, x1))) + r;
  const int ymin = int(std::floor(std::min(y0, y1))) - r, ymax = int(std::ceil(std::max(y0, y1))) + r;
  for (int y = ymin; y <= ymax; ++y)
    for (int x = xmin; x <= xmax; ++x) {
      const double px = x + 0.5 - x0, py = y + 0.5 - y0;
      const double t = std::clamp((px * dx + py * dy) / len2, 0.0, 1.0);
      const double ex = px - t * dx, ey = py - t * dy, d2 = ex * ex + ey * ey;
      const int wx = ((x % n) + n) % n, wy = ((y % n) + n) % n;
      h[std::size_t(wy) * n + wx] -= depth * std::exp(-d2 / (w * w));
    }
}

}  // namespace

texture::Level height_field(Pattern p, int size) {
  if (size < 16 || (size & (size - 1)))
    throw std::invalid_argument("height_field: size must be a power of two >= 16");
  const int n = size;
  std::vector<double> h(std::size_t(n) * n, 0.0);
  Rng rng{p == Pattern::Rivets ? 0x5EEDull : 0xBEEFull};
  if (p == Pattern::Rivets) {
    const int grid = 8;
    const double cell = double(n) / grid, radius = 0.32 * cell, height = 0.22 * cell;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double cx = wrap(x + 0.5 - cell * 0.5, cell), cy = wrap(y + 0.5 - cell * 0.5, cell);
        const double d = std::sqrt(cx * cx + cy * cy) / radius;
        double v = d < 1 ? height * (1 - d * d) * (1 - d * d) : 0.0;
        // A plate with a fine grain: two high-frequency ripples.
        v += 0.25 * std::sin(2 * M_PI * (x + 0.5) * 21 / n) * std::sin(2 * M_PI * (y + 0.5) * 17 / n);
        h[std::size_t(y) * n + x] = v;
      }
    for (int k = 0; k < 40; ++k) {
      const double x0 = rng.next() * n, y0 = rng.next() * n, a = rng.next() * 2 * M_PI,
                   l = (0.1 + 0.3 * rng.next()) * n;
      scratch(h, n, x0, y0, x0 + l * std::cos(a), y0 + l * std::sin(a), 0.6 + 0.6 * rng.next(), 0.9);
    }
  } else {
    for (int k = 0; k < 220; ++k) {
      const double cx = rng.next() * n, cy = rng.next() * n, r = (0.03 + 0.05 * rng.next()) * n;
      const double depth = 0.35 * r;
      const int ri = int(std::ceil(r));
      for (int y = int(cy) - ri; y <= int(cy) + ri; ++y)
        for (int x = int(cx) - ri; x <= int(cx) + ri; ++x) {
          const double dx = x + 0.5 - cx, dy = y + 0.5 - cy, d = std::sqrt(dx * dx + dy * dy) / r;
          if (d >= 1) continue;
          const int wx = ((x % n) + n) % n, wy = ((y % n) + n) % n;
          double& v = h[std::size_t(wy) * n + wx];
          v = std::min(v, -depth * (1 - d * d) * (1 - d * d));  // overlapping dimples: the deepest wins
        }
    }
    for (int k = 0; k < 60; ++k) {
      const double x0 = rng.next() * n, y0 = rng.next() * n, a = 0.3 * (rng.next() - 0.5),
                   l = (0.2 + 0.5 * rng.next()) * n;
      scratch(h, n, x0, y0, x0 + l * std::cos(a), y0 + l * std::sin(a), 0.4 + 0.4 * rng.next(), 0.8);
    }
  }
  texture::Level out{n, n, 1, std::vector<float>(h.begin(), h.end())};
  return out;
}

texture::Level normal_map(Pattern p, int size) {
  const texture::Level h = height_field(p, size);
  const int n = size;
  texture::Level out{n, n, 3, std::vector<float>(std::size_t(n) * n * 3)};
  auto H = [&](int x, int y) { return double(h.at(((x % n) + n) % n, ((y % n) + n) % n, 0)); };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double gx = 0.5 * (H(x + 1, y) - H(x - 1, y)), gy = 0.5 * (H(x, y + 1) - H(x, y - 1));
      const double len = std::sqrt(gx * gx + gy * gy + 1);
      const double nv[3] = {-gx / len, -gy / len, 1 / len};
      for (int c = 0; c < 3; ++c) {
        // Quantize here so the stored bytes are exactly what the renderer reads back.
        const double e = std::round((nv[c] * 0.5 + 0.5) * 255.0) / 255.0;
        out.texels[(std::size_t(y) * n + x) * 3 + c] = float(e);
      }
    }
  return out;
}

void write_png8(const std::string& path, const texture::Level& lvl) {
  if (lvl.channels != 3) throw std::runtime_error("write_png8 '" + path + "': needs 3 channels");
  std::vector<unsigned char> bytes(lvl.texels.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<unsigned char>(std::lround(std::clamp(lvl.texels[i], 0.f, 1.f) * 255.f));
  const std::string tmp = path + ".tmp.png";
  auto out = OIIO::ImageOutput::create(tmp);
  if (!out) throw std::runtime_error("cannot write '" + path + "': " + OIIO::geterror());
  OIIO::ImageSpec spec(lvl.width, lvl.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "Linear");
  if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) || !out->close())
    throw std::runtime_error("cannot write '" + path + "': " + out->geterror());
  std::filesystem::rename(tmp, path);
}

}  // namespace bl::normalmap
