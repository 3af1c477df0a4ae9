// A texture as the smoothed shaders see it (clamped-domain paper, Section 4.3): two pyramids built
// once at load time, the mean of the texel values (eq. 21) and the mean of their squares, so a lookup
// at the footprint's level returns a mean and a variance E[p^2] - E[p]^2 (eq. 22) that the rules
// downstream consume like any other random value.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "texture/pyramid.hpp"

namespace bl::texture {

// Every load failure names the file: missing, unreadable, wrong channel count, bad size.
class TextureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Encoding {
  Srgb,   // 8/16-bit colour images: display-encoded, decoded to linear on load
  Linear  // data (normal maps, heights) and float files: taken as stored
};

struct Texture {
  std::string name;                // the slot name shaders use ("albedo")
  std::string file;                // where it came from (for messages and cache keys)
  std::uint64_t content_hash = 0;  // FNV-1a of the linear texels (cache keys)
  Pyramid mean;                    // mean of values
  Pyramid squares;                 // mean of squares

  int channels() const { return mean.channels(); }
  // Direct sampling: bilinear on level 0 (what an unsmoothed shader does).
  float plain(float u, float v, int c) const { return mean.bilinear(0, u, v, c); }
};

// Builds both pyramids from a level-0 image (throws TextureError naming `file`).
Texture make_texture(std::string name, std::string file, Level base);

// Reads `file` with OpenImageIO. `channels` is the count the shader needs: the file must have
// exactly that many (a 4-channel file for a 3-channel slot is rejected, not silently cut).
Texture load_texture(const std::string& name, const std::string& file, int channels, Encoding enc);

// The textures a shader binds, by slot (index = the slot number in the traced graph).
using Bindings = std::vector<std::shared_ptr<const Texture>>;

// The texture bound to slot `name`, or null: the one lookup by name (native shaders, scenes).
inline const Texture* find(const Bindings& b, const std::string& name) {
  for (const auto& t : b)
    if (t && t->name == name) return t.get();
  return nullptr;
}

}  // namespace bl::texture
