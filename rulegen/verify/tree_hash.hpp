// blverify: the identity of a generated tree together with the verification code compiled against
// it: FNV-1a 64 over the ABI tag and the names and bytes of DIR/bandlimit/*, the plugin sources and
// rulegen/templates/*. Equal hashes: the same plugin. Header-only (blverify and blverify_treehash).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace blv {

inline void fnv1a(std::uint64_t& h, const std::string& bytes) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  h ^= 0xff;  // separator, so that ("ab", "c") and ("a", "bc") differ
  h *= 1099511628211ull;
}

// Regular files directly in dir (sorted), or in dir and below when recursive.
inline std::vector<std::filesystem::path> files_in(const std::filesystem::path& dir, bool recursive) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  if (recursive) {
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir, ec))
      if (e.is_regular_file()) out.push_back(e.path());
  } else {
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
      if (e.is_regular_file()) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// generated_dir: the tree (its bandlimit/ headers); verify_dir: rulegen/verify; templates_dir:
// rulegen/templates.
inline std::string tree_hash(const std::string& generated_dir, const std::string& verify_dir,
                             const std::string& templates_dir, int abi) {
  std::uint64_t h = 1469598103934665603ull;
  fnv1a(h, "blverify tree abi " + std::to_string(abi));
  auto add = [&h](const std::filesystem::path& root, const std::vector<std::filesystem::path>& files) {
    for (const auto& f : files) {
      fnv1a(h, std::filesystem::relative(f, root).generic_string());
      fnv1a(h, file_bytes(f));
    }
  };
  add(generated_dir, files_in(std::filesystem::path(generated_dir) / "bandlimit", false));
  std::vector<std::filesystem::path> src;
  for (const auto& f : files_in(verify_dir, true))
    if (f.extension() == ".cpp" || f.extension() == ".hpp") src.push_back(f);
  add(verify_dir, src);
  add(templates_dir, files_in(templates_dir, false));
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace blv
