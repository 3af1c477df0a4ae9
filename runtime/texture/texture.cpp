#include "texture/texture.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>

#include "image/display.hpp"
#include "ir/hash.hpp"

namespace bl::texture {

Texture make_texture(std::string name, std::string file, Level base) {
  Texture t;
  t.name = std::move(name);
  t.file = std::move(file);
  for (float x : base.texels)
    if (!std::isfinite(x)) throw TextureError("texture '" + t.file + "': non-finite texel value");
  const std::string_view bytes(reinterpret_cast<const char*>(base.texels.data()),
                               base.texels.size() * sizeof(float));
  t.content_hash = ir::fnv1a(bytes, ir::fnv1a(std::to_string(base.width) + "x" + std::to_string(base.height) +
                                              "x" + std::to_string(base.channels)));
  Level sq = base;
  for (float& x : sq.texels) x *= x;
  try {
    t.mean = Pyramid(std::move(base));
    t.squares = Pyramid(std::move(sq));
  } catch (const std::invalid_argument& e) {
    throw TextureError("texture '" + t.file + "': " + e.what());
  }
  return t;
}

Texture load_texture(const std::string& name, const std::string& file, int channels, Encoding enc) {
  if (!std::filesystem::exists(file))
    throw TextureError("texture '" + file + "' (slot " + name + "): no such file");
  auto in = OIIO::ImageInput::open(file);
  if (!in) throw TextureError("texture '" + file + "' (slot " + name + "): cannot read: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels != channels)
    throw TextureError("texture '" + file + "' (slot " + name + "): has " + std::to_string(spec.nchannels) +
                       " channels, the shader needs " + std::to_string(channels));
  Level base;
  base.width = spec.width;
  base.height = spec.height;
  base.channels = channels;
  base.texels.resize(std::size_t(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, base.texels.data()))
    throw TextureError("texture '" + file + "' (slot " + name + "): cannot read pixels: " + in->geterror());
  const bool is_float =
      spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF;
  if (enc == Encoding::Srgb && !is_float)
    for (float& x : base.texels) x = from_display(x);
  // Files store row 0 at the top; texture coordinate v grows with the row index here as well, so
  // the image is used as stored (v = 0 is the file's first row).
  return make_texture(name, file, std::move(base));
}

}  // namespace bl::texture
