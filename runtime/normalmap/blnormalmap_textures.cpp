// blnormalmap_textures: writes the procedural normal maps (generate.hpp) as 8-bit PNGs.
//
//   blnormalmap_textures --out scenes/textures [--size 256]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "normalmap/generate.hpp"

int main(int argc, char** argv) {
  CLI::App app{"blnormalmap_textures: regenerate the procedural normal maps"};
  std::string out = "scenes/textures";
  int size = 256;
  app.add_option("--out", out, "output directory");
  app.add_option("--size", size, "side in texels (a power of two)");
  CLI11_PARSE(app, argc, argv);
  try {
    std::filesystem::create_directories(out);
    using bl::normalmap::Pattern;
    for (auto [p, name] :
         {std::pair{Pattern::Rivets, "nm_rivets.png"}, std::pair{Pattern::Hammered, "nm_hammered.png"}}) {
      const std::string path = out + "/" + name;
      bl::normalmap::write_png8(path, bl::normalmap::normal_map(p, size));
      std::printf("wrote %s (%lld bytes)\n", path.c_str(), (long long)std::filesystem::file_size(path));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blnormalmap_textures: %s\n", e.what());
    return 1;
  }
  return 0;
}
