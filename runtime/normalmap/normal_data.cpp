#include "normalmap/normal_data.hpp"

#include <algorithm>
#include <cmath>

#include "texture/texture.hpp"

namespace bl::normalmap {

int lobe_cell(double nx, double ny, double nz, const LobeGrid& grid, double max_polar) {
  const double polar = std::acos(std::clamp(nz, -1.0, 1.0));
  double az = std::atan2(ny, nx);  // (-pi, pi]
  if (az < 0) az += 2 * M_PI;
  int lon = std::min(grid.longitude - 1, static_cast<int>(az / (2 * M_PI) * grid.longitude));
  int lat =
      max_polar > 0 ? std::min(grid.latitude - 1, static_cast<int>(polar / max_polar * grid.latitude)) : 0;
  return lat * grid.longitude + std::max(0, lon);
}

NormalMapData build_normal_map(const texture::Level& encoded, const std::string& file, LobeGrid grid) {
  if (encoded.channels != 3)
    throw texture::TextureError("normal map '" + file + "': has " + std::to_string(encoded.channels) +
                                " channels, a normal map needs 3");
  if (grid.longitude < 1 || grid.latitude < 1)
    throw texture::TextureError("normal map '" + file + "': the lobe grid needs at least 1x1 cells");
  const std::size_t n = std::size_t(encoded.width) * encoded.height;
  texture::Level nl{encoded.width, encoded.height, 3, std::vector<float>(n * 3)};
  texture::Level ll{encoded.width, encoded.height, 5, std::vector<float>(n * 5)};
  texture::Level cl{encoded.width, encoded.height, 4 * grid.cells(),
                    std::vector<float>(n * 4 * grid.cells(), 0.f)};
  NormalMapData d;
  d.file = file;
  d.grid = grid;
  std::vector<double> unit(n * 3);
  for (std::size_t i = 0; i < n; ++i) {
    double v[3];
    for (int c = 0; c < 3; ++c) v[c] = 2.0 * encoded.texels[i * 3 + c] - 1.0;
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len > 0) || v[2] / len <= 0.01) {
      const int x = int(i % encoded.width), y = int(i / encoded.width);
      throw texture::TextureError(
          "normal map '" + file + "': texel (" + std::to_string(x) + ", " + std::to_string(y) +
          ") decodes to a normal that does not face out of the surface (n_z <= 0.01): "
          "not a tangent-space normal map encoded as n * 0.5 + 0.5?");
    }
    for (int c = 0; c < 3; ++c) unit[i * 3 + c] = v[c] / len;
    d.max_polar = std::max(d.max_polar, std::acos(std::min(1.0, unit[i * 3 + 2])));
  }
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) {
    const double nx = unit[i * 3], ny = unit[i * 3 + 1], nz = unit[i * 3 + 2];
    for (int c = 0; c < 3; ++c) nl.texels[i * 3 + c] = float(unit[i * 3 + c]);
    const double bx = nx / nz, by = ny / nz;
    const double m[5] = {bx, by, bx * bx, by * by, bx * by};
    for (int c = 0; c < 5; ++c) ll.texels[i * 5 + c] = float(m[c]);
    const int cell = lobe_cell(nx, ny, nz, grid, d.max_polar * (1 + 1e-9));
    float* cp = &cl.texels[(i * grid.cells() + cell) * 4];
    cp[0] = 1.f, cp[1] = float(nx), cp[2] = float(ny), cp[3] = float(nz);
    for (int c = 0; c < 3; ++c) {
      const float f = encoded.texels[i * 3 + c];
      const unsigned char* b = reinterpret_cast<const unsigned char*>(&f);
      for (int k = 0; k < 4; ++k) h = (h ^ b[k]) * 1099511628211ull;
    }
  }
  d.content_hash = h;
  try {
    d.normals = texture::Pyramid(std::move(nl));
    d.lean = texture::Pyramid(std::move(ll));
    d.lobes = texture::Pyramid(std::move(cl));
  } catch (const std::invalid_argument& e) {
    throw texture::TextureError("normal map '" + file + "': " + e.what());
  }
  return d;
}

NormalMapData load_normal_map(const std::string& file, LobeGrid grid) {
  const texture::Texture t = texture::load_texture("normal", file, 3, texture::Encoding::Linear);
  return build_normal_map(t.mean.level(0), file, grid);
}

}  // namespace bl::normalmap
