#include "image/image_io.hpp"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "image/display.hpp"

namespace bl {
namespace fs = std::filesystem;
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void require_extension(const std::string& path, const char* ext, const char* writer) {
  if (lower_extension(path) != ext) {
    throw ImageError(std::string(writer) + ": '" + path + "' must end in " + ext);
  }
}

// Same directory (so rename is atomic) and same extension (OpenImageIO picks the format by it).
fs::path temp_name(const fs::path& target) {
  static std::atomic<int> counter{0};
  const std::string name = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                           std::to_string(counter++) + target.extension().string();
  return target.parent_path() / name;
}

void write_atomically(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc data_type,
                      const void* data) {
  const fs::path target(path);
  const fs::path tmp = temp_name(target);
  std::string error;
  {
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) {
      throw ImageError("cannot write '" + path + "': " + OIIO::geterror());
    }
    if (!out->open(tmp.string(), spec) || !out->write_image(data_type, data) || !out->close()) {
      error = out->geterror();
      if (error.empty()) error = OIIO::geterror();
    }
  }
  std::error_code ec;
  if (error.empty()) {
    fs::rename(tmp, target, ec);
    if (ec) error = "rename from " + tmp.string() + ": " + ec.message();
  }
  if (!error.empty()) {
    fs::remove(tmp, ec);
    throw ImageError("cannot write '" + path + "': " + error);
  }
}

}  // namespace

Image read_image(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw ImageError("cannot read '" + path + "': no such file");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw ImageError("cannot read '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels != 3 && spec.nchannels != 4) {
    throw ImageError("cannot read '" + path + "': it has " + std::to_string(spec.nchannels) +
                     " channels, expected 3 (RGB) or 4 (RGBA)");
  }
  if (spec.depth > 1) throw ImageError("cannot read '" + path + "': volume images are not supported");
  const int nch = spec.nchannels;
  std::vector<float> raw(size_t(spec.width) * spec.height * nch);
  if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, raw.data())) {
    throw ImageError("cannot read '" + path + "': " + in->geterror());
  }
  const bool linear = spec.format.is_floating_point();
  Image img(spec.width, spec.height);
  for (size_t p = 0; p < size_t(spec.width) * spec.height; ++p) {
    for (int c = 0; c < 3; ++c) {
      const float v = raw[p * nch + c];
      img.pixels[3 * p + c] = linear ? v : from_display(v);
    }
  }
  return img;
}

void write_exr(const std::string& path, const Image& img) {
  require_extension(path, ".exr", "write_exr");
  OIIO::ImageSpec spec(img.width, img.height, Image::kChannels, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  write_atomically(path, spec, OIIO::TypeDesc::FLOAT, img.pixels.data());
}

void write_png(const std::string& path, const Image& img, const std::string& description) {
  require_extension(path, ".png", "write_png");
  std::vector<unsigned char> bytes(img.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<unsigned char>(std::lround(to_display(img.pixels[i]) * 255.0f));
  }
  OIIO::ImageSpec spec(img.width, img.height, Image::kChannels, OIIO::TypeDesc::UINT8);
  if (!description.empty()) spec.attribute("ImageDescription", description);
  write_atomically(path, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

void write_image(const std::string& path, const Image& img) {
  const std::string ext = lower_extension(path);
  if (ext == ".exr") return write_exr(path, img);
  if (ext == ".png") return write_png(path, img);
  throw ImageError("write_image: '" + path + "': unsupported extension (use .exr or .png)");
}

}  // namespace bl
