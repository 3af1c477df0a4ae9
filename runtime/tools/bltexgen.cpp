// bltexgen: writes the project's procedural colour texture (scenes/textures/albedo_cells.png):
// Voronoi cells of random colours with dark borders and a fine speckle, so that minification
// aliases badly without filtering. Deterministic (integer hashes, no library RNG), so rerunning it
// reproduces the committed file bit for bit.
//
//   bltexgen --out scenes/textures/albedo_cells.png --size 256
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "image/image_io.hpp"

namespace {

std::uint32_t hash(std::uint32_t x) {  // Chris Wellons' lowbias32
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}
double unit(std::uint32_t h) {
  return (h >> 8) * (1.0 / 16777216.0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bltexgen: the procedural colour texture of the texture scenes"};
  std::string out = "scenes/textures/albedo_cells.png";
  int size = 256, cells = 8;
  app.add_option("--out", out, "output PNG");
  app.add_option("--size", size, "side in texels (a power of two)")->check(CLI::Range(8, 4096));
  app.add_option("--cells", cells, "cells per side")->check(CLI::Range(1, 256));
  CLI11_PARSE(app, argc, argv);
  try {
    bl::Image img(size, size);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        // Distances to the two nearest feature points of a jittered grid that wraps (tileable).
        const double px = (x + 0.5) * cells / size, py = (y + 0.5) * cells / size;
        const int cx = static_cast<int>(px), cy = static_cast<int>(py);
        double d1 = 1e9, d2 = 1e9;
        std::uint32_t id = 0;
        for (int j = -1; j <= 1; ++j)
          for (int i = -1; i <= 1; ++i) {
            const int gx = cx + i, gy = cy + j;
            const std::uint32_t cell =
                static_cast<std::uint32_t>(((gy + cells) % cells) * cells + (gx + cells) % cells);
            const double fx = gx + unit(hash(2 * cell + 1)), fy = gy + unit(hash(2 * cell + 2));
            const double d = std::hypot(px - fx, py - fy);
            if (d < d1) {
              d2 = d1;
              d1 = d;
              id = cell;
            } else if (d < d2) {
              d2 = d;
            }
          }
        const double border = d2 - d1 < 0.06 ? 0.15 : 1.0;
        const double speckle = 0.8 + 0.4 * unit(hash(static_cast<std::uint32_t>(y * size + x) ^ 0x9e3779b9U));
        for (int c = 0; c < 3; ++c) {
          const double base = 0.15 + 0.8 * unit(hash(id * 3 + static_cast<std::uint32_t>(c) + 77));
          img.at(x, y, c) = static_cast<float>(std::min(1.0, base * border * speckle));
        }
      }
    bl::write_png(out, img, "bandlimit procedural albedo (bltexgen)");
    std::printf("wrote %s (%dx%d, %d cells per side)\n", out.c_str(), size, size, cells);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bltexgen: %s\n", e.what());
    return 1;
  }
  return 0;
}
