// Deterministic procedural normal maps (tangent space, n * 0.5 + 0.5), made from periodic height
// fields by central differences, so they tile. Both are dense in small, steep features whose
// specular highlights alias badly when the plane is minified:
//   rivets:   an 8x8 grid of domed rivets on a plate, with fine scratches and a light grain;
//   hammered: randomly placed overlapping dimples (hammered metal), with scratches.
// The random numbers come from splitmix64 with a fixed seed (no std:: distributions, whose output
// is implementation-defined), so every platform writes the same bytes.
#pragma once

#include <string>

#include "texture/pyramid.hpp"

namespace bl::normalmap {

enum class Pattern { Rivets, Hammered };

// Height field (texel units) of `size` x `size` texels (size a power of two).
texture::Level height_field(Pattern p, int size);
// Tangent-space unit normals encoded as n * 0.5 + 0.5, 3 channels, from the height field.
texture::Level normal_map(Pattern p, int size);

// Writes `lvl` (3 channels in [0, 1]) as an 8-bit PNG without any transfer function (data, not
// colour). Throws std::runtime_error naming the file.
void write_png8(const std::string& path, const texture::Level& lvl);

}  // namespace bl::normalmap
