// The per-level data every technique reads, built once from a normal map's decoded unit normals,
// all as bl::texture::Pyramid (box mips, GL trilinear/repeat lookups):
//   normals: the averaged (unnormalized) normal, 3 channels: Toksvig's and eqs. 24-25's N;
//   lean:    Olano & Baker's moments of the slopes b = (n_x/n_z, n_y/n_z): (b_x, b_y, b_x^2, b_y^2,
//            b_x b_y), 5 channels;
//   lobes:   the multi-lobe cells (Sec. 4.3.1): the normals' directions partitioned into
//            `longitude` azimuth sectors x `latitude` polar bands (bands equal in the polar angle over
//            [0, max polar angle of the map]); per cell c, 4 channels (w_c, w_c N_c): the share of
//            texels in the cell and that share times the cell's averaged normal, so the mip average
//            of a level stays the share and share-weighted mean of the texels it covers.
#pragma once

#include <string>

#include "texture/pyramid.hpp"

namespace bl::normalmap {

struct LobeGrid {
  int longitude = 4, latitude = 2;
  int cells() const { return longitude * latitude; }
};

struct NormalMapData {
  std::string file;
  std::uint64_t content_hash = 0;
  texture::Pyramid normals, lean, lobes;
  LobeGrid grid;
  double max_polar = 0;  // radians, the largest polar angle of any texel's normal

  int width() const { return normals.width(); }
  int height() const { return normals.height(); }
};

// Decodes an 8/16-bit or float 3-channel texture stored as n * 0.5 + 0.5 (tangent space, z up),
// renormalizes each texel and builds the pyramids. `base` is level 0 as loaded (3 channels).
// Throws texture::TextureError naming `file` for a texel with n_z <= 0 after decoding.
NormalMapData build_normal_map(const texture::Level& encoded, const std::string& file, LobeGrid grid);

// load_texture(file, 3 channels, linear) + build_normal_map: every error names the file (missing,
// unreadable, wrong channel count, not a power of two, back-facing texels).
NormalMapData load_normal_map(const std::string& file, LobeGrid grid);

// The cell index of a unit normal (tangent space) for a grid and max polar angle.
int lobe_cell(double nx, double ny, double nz, const LobeGrid& grid, double max_polar);

}  // namespace bl::normalmap
