// blverify_treehash GENERATED_DIR VERIFY_DIR TEMPLATES_DIR OUT.hpp: writes the tree hash of the
// project's tree for the plugin CMake builds (so blverify recognises it and compiles nothing).
#include <fstream>

#include "tree_api.hpp"
#include "tree_hash.hpp"

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  const std::string h = blv::tree_hash(argv[1], argv[2], argv[3], blv::kTreeAbi);
  const std::string text = "#define BLVERIFY_TREE_HASH \"" + h + "\"\n";
  {
    std::ifstream in(argv[4]);
    std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (old == text) return 0;  // unchanged: no rebuild of the plugin
  }
  std::ofstream(argv[4]) << text;
  return 0;
}
